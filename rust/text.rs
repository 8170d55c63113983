//! Numbers and names as the core's messages write them: the way Python writes them, since that
//! is how the user gave them (`repr`) and how clearsim's Python messages print them (`:.3g`).

/// A number as it appears in a message (`repr`): one definition, in [`crate::error`] (below
/// the compiler, so that the constraints' checks write numbers the same way).
pub(crate) use crate::error::num;

/// `v` with `precision` significant digits as Python's `format(v, ".{precision}g")` writes it:
/// fixed notation for exponents −4 ≤ X < precision, else `1.5e-07`; no trailing zeros.
pub(crate) fn g(v: f64, precision: usize) -> String {
    if v.is_nan() {
        return "nan".to_string();
    }
    if v.is_infinite() {
        return (if v > 0.0 { "inf" } else { "-inf" }).to_string();
    }
    let p = precision.max(1);
    let e = format!("{:.*e}", p - 1, v); // rounded to p significant digits: "1.50e-7"
    let (mantissa, exp) = e.split_once('e').unwrap_or((&e, "0"));
    let x: i32 = exp.parse().unwrap_or(0);
    if -4 <= x && x < p as i32 {
        let fixed = format!("{:.*}", (p as i32 - 1 - x).max(0) as usize, v);
        trim(&fixed).to_string()
    } else {
        exponent_form(trim(mantissa), exp)
    }
}

/// A string as Python's `repr` writes it: `'crank'` (or `"it's"`).
pub(crate) fn quoted(s: &str) -> String {
    if s.contains('\'') && !s.contains('"') {
        format!("\"{s}\"")
    } else {
        format!("'{}'", s.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

/// Trailing zeros (and a trailing point) of a decimal fraction removed.
fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// `mantissa` and a Rust exponent (`-7`) as Python writes them: `e-07`, `e+20`.
fn exponent_form(mantissa: &str, exp: &str) -> String {
    let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
    format!("{mantissa}e{sign}{digits:0>2}")
}

#[cfg(test)]
mod tests {
    #[test]
    fn numbers_as_python_writes_them() {
        for (v, text) in [(2.0, "2.0"), (0.0, "0.0"), (-0.001, "-0.001"), (1e-6, "1e-06"), (-1.5e-7, "-1.5e-07"), (1e20, "1e+20"), (1e-300, "1e-300"), (1e15, "1000000000000000.0"), (f64::NAN, "nan"), (f64::NEG_INFINITY, "-inf")] {
            assert_eq!(super::num(v), text);
        }
    }

    /// Each value as Python 3.11 prints `format(v, ".3g")`, `".4g"`, `".1g"` and `"g"`.
    #[test]
    fn significant_digits_as_python_writes_them() {
        let cases: [(f64, usize, &str); 22] = [
            (0.02, 3, "0.02"),
            (0.14, 3, "0.14"),
            (300.0, 3, "300"),
            (1e-6, 1, "1e-06"),
            (1.2345e-6, 3, "1.23e-06"),
            (0.000123456, 3, "0.000123"),
            (123456.0, 3, "1.23e+05"),
            (999.6, 3, "1e+03"),
            (99.96, 3, "100"),
            (0.5, 3, "0.5"),
            (-0.0311, 3, "-0.0311"),
            (2.0, 3, "2"),
            (0.0, 3, "0"),
            (12.5, 4, "12.5"),
            (0.04, 4, "0.04"),
            (-0.06, 4, "-0.06"),
            (0.2, 6, "0.2"),
            (0.0075, 6, "0.0075"),
            (1e-3, 6, "0.001"),
            (1234567.0, 6, "1.23457e+06"),
            (10.0, 6, "10"),
            (5e-7, 6, "5e-07"),
        ];
        for (v, p, text) in cases {
            assert_eq!(super::g(v, p), text, "{v} .{p}g");
        }
        assert_eq!(super::quoted("crank"), "'crank'");
        assert_eq!(super::quoted("it's"), "\"it's\"");
    }
}
