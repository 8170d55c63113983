//! The names by which a description's elements refer to one another (a joint's bodies, a
//! driver's body, a load table's driver), resolved into the indices of [`MechanismDesc`]
//! ([`resolve`]) and back ([`unresolve`], for a description handed back: the ideal counterpart).
//!
//! The Python layer and scene files describe a mechanism by names, the ground as `"ground"`;
//! resolution runs on the plain data before it is read into the typed description, when the
//! mechanism compiles, so elements may be defined in any order. A reference already given as
//! an index (a JSON fixture, a Rust user) is left as it is. An unknown name is an
//! [`Error::InvalidInput`] naming the element and its field, e.g. `force 'gas'.value.driver`.
//!
//! [`MechanismDesc`]: crate::description::MechanismDesc

use std::collections::HashMap;

use serde_json::Value;

use crate::text::quoted;
use crate::error::{Error, Result};

/// The fixed frame's name.
pub const GROUND: &str = "ground";

/// Per element list: its fields that name a body, and whether the ground may be named there.
const BODY_FIELDS: [(&str, &[(&str, bool)]); 4] = [
    ("joints", &[("body_a", true), ("body_b", true)]),
    ("drivers", &[("body", false)]),
    ("clearance_joints", &[("bearing_body", true), ("journal_body", true)]),
    ("prismatic_clearance_joints", &[("guide_body", true), ("slider_body", false)]),
];

/// A force element's kind: how messages call it and its fields that name a body.
fn force_fields(kind: &str) -> (&'static str, &'static [(&'static str, bool)]) {
    match kind {
        "spring_damper" => ("spring", &[("body_a", true), ("body_b", true)]),
        "rotational_spring_damper" => ("rotational spring", &[("body_a", true), ("body_b", true)]),
        "torque" => ("torque", &[("body", false), ("reaction", true)]),
        "motor" => ("motor", &[("body", false), ("reaction", true)]),
        _ => ("force", &[("body", false)]),
    }
}

/// A force element's load profiles, which may be tables in a driver's (or body's) angle.
const PROFILES: [&str; 3] = ["fx", "fy", "magnitude"];

/// How messages name an element of `group`: `joint 'crank-rod'`, `spring 'k1'`, ...
pub fn label(group: &str, entry: &Value) -> String {
    let name = entry.get("name").and_then(Value::as_str).unwrap_or("?");
    let kind = match group {
        "forces" => force_fields(entry.get("kind").and_then(Value::as_str).unwrap_or("")).0,
        "joints" => "joint",
        "drivers" => "driver",
        "bodies" => "body",
        _ => "clearance joint",
    };
    format!("{kind} '{name}'")
}

/// The fields of an element of `group` that name a body (ground allowed or not).
pub fn body_fields(group: &str, entry: &Value) -> &'static [(&'static str, bool)] {
    if group == "forces" {
        return force_fields(entry.get("kind").and_then(Value::as_str).unwrap_or("")).1;
    }
    BODY_FIELDS.iter().find(|(g, _)| *g == group).map_or(&[], |(_, f)| *f)
}

/// Replace the body and driver names in the description `v` by body indices (the ground:
/// `null`), and fill a constant-speed driver's missing `angle0` with its body's angle.
pub fn resolve(v: &mut Value) -> Result<()> {
    let Some(top) = v.as_object_mut() else { return Ok(()) };
    let bodies: Vec<(String, f64)> = top
        .get("bodies")
        .and_then(Value::as_array)
        .map(|b| b.iter().map(|b| (b.get("name").and_then(Value::as_str).unwrap_or("").to_string(), b.get("angle").and_then(Value::as_f64).unwrap_or(0.0))).collect())
        .unwrap_or_default();
    let index: HashMap<&str, usize> = bodies.iter().enumerate().map(|(k, (n, _))| (n.as_str(), k)).collect();
    let names: Vec<&str> = bodies.iter().map(|(n, _)| n.as_str()).collect();
    let body = |where_: &str, value: &mut Value, ground: bool| -> Result<()> {
        let Some(name) = value.as_str() else { return Ok(()) }; // an index or null: resolved already
        if name == GROUND && ground {
            *value = Value::Null;
            return Ok(());
        }
        match index.get(name) {
            Some(&k) => {
                *value = Value::from(k);
                Ok(())
            }
            None => {
                let known = if ground { std::iter::once(GROUND).chain(names.iter().copied()).collect::<Vec<_>>() } else { names.clone() };
                let known = if known.is_empty() { "none".to_string() } else { known.join(", ") };
                let why = if name == GROUND { "the ground cannot be driven or slide" } else { "no such body" };
                Err(Error::invalid(where_, quoted(name), format!("{why} (known: {known})")))
            }
        }
    };
    for (group, _) in BODY_FIELDS {
        for entry in top.get_mut(group).and_then(Value::as_array_mut).into_iter().flatten() {
            let what = label(group, entry);
            for &(key, ground) in body_fields(group, entry) {
                if let Some(value) = entry.get_mut(key) {
                    body(&format!("{what}.{key}"), value, ground)?;
                }
            }
        }
    }
    // A driver or motor → the body it turns (for load tables in its angle).
    let mut turned: Vec<(String, Value)> = Vec::new();
    for d in top.get("drivers").and_then(Value::as_array).into_iter().flatten() {
        turned.push((d.get("name").and_then(Value::as_str).unwrap_or("").to_string(), d.get("body").cloned().unwrap_or(Value::Null)));
    }
    for entry in top.get_mut("forces").and_then(Value::as_array_mut).into_iter().flatten() {
        let what = label("forces", entry);
        for &(key, ground) in body_fields("forces", entry) {
            if let Some(value) = entry.get_mut(key) {
                body(&format!("{what}.{key}"), value, ground)?;
            }
        }
        if entry.get("kind").and_then(Value::as_str) == Some("motor") {
            turned.push((entry.get("name").and_then(Value::as_str).unwrap_or("").to_string(), entry.get("body").cloned().unwrap_or(Value::Null)));
        }
    }
    for entry in top.get_mut("forces").and_then(Value::as_array_mut).into_iter().flatten() {
        let what = label("forces", entry);
        for key in PROFILES {
            let Some(argument) = entry.get_mut(key).and_then(|p| p.get_mut("argument")).and_then(Value::as_object_mut) else { continue };
            if argument.get("kind").and_then(Value::as_str) != Some("angle") {
                continue;
            }
            if let Some(value) = argument.get_mut("body") {
                body(&format!("{what}.{key}.argument.body"), value, false)?;
            } else if let Some(name) = argument.remove("driver") {
                let name = name.as_str().unwrap_or("").to_string();
                let Some((_, b)) = turned.iter().find(|(n, _)| *n == name) else {
                    let known = if turned.is_empty() { "none".to_string() } else { turned.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ") };
                    return Err(Error::invalid(format!("{what}.value.driver"), quoted(&name), format!("no such driver or motor (known: {known})")));
                };
                argument.insert("body".into(), b.clone());
            }
        }
    }
    for d in top.get_mut("drivers").and_then(Value::as_array_mut).into_iter().flatten() {
        let b = d.get("body").and_then(Value::as_u64).map(|b| b as usize);
        let Some(law) = d.get_mut("law").and_then(Value::as_object_mut) else { continue };
        if law.get("kind").and_then(Value::as_str) == Some("constant_speed") && law.get("angle0").is_none_or(Value::is_null) {
            if let Some((_, angle)) = b.and_then(|b| bodies.get(b)) {
                law.insert("angle0".into(), Value::from(*angle));
            }
        }
    }
    Ok(())
}

/// The inverse of [`resolve`] on a description written back as plain data: each body index
/// replaced by the body's name (`null`: `"ground"`; a torque's or motor's `reaction` stays
/// `null`, which [`resolve`] reads alike), a load table's angle argument naming its body.
pub fn unresolve(v: &mut Value) {
    let Some(top) = v.as_object_mut() else { return };
    let names: Vec<String> = top
        .get("bodies")
        .and_then(Value::as_array)
        .map(|b| b.iter().map(|b| b.get("name").and_then(Value::as_str).unwrap_or("").to_string()).collect())
        .unwrap_or_default();
    let name = |value: &mut Value| match value.as_u64() {
        Some(k) => *value = Value::from(names.get(k as usize).cloned().unwrap_or_default()),
        None if value.is_null() => *value = Value::from(GROUND),
        None => {}
    };
    for (group, _) in BODY_FIELDS {
        for entry in top.get_mut(group).and_then(Value::as_array_mut).into_iter().flatten() {
            for &(key, _) in body_fields(group, entry) {
                if let Some(value) = entry.get_mut(key) {
                    name(value);
                }
            }
        }
    }
    for entry in top.get_mut("forces").and_then(Value::as_array_mut).into_iter().flatten() {
        for &(key, _) in body_fields("forces", entry) {
            if let Some(value) = entry.get_mut(key) {
                if !(key == "reaction" && value.is_null()) {
                    name(value);
                }
            }
        }
        for key in PROFILES {
            if let Some(argument) = entry.get_mut(key).and_then(|p| p.get_mut("argument")).and_then(Value::as_object_mut) {
                if argument.get("kind").and_then(Value::as_str) == Some("angle") {
                    if let Some(value) = argument.get_mut("body") {
                        name(value);
                    }
                }
            }
        }
    }
}

/// `entry` (one element of `group`, as added: its references still names) with every body
/// reference set to a placeholder the typed description accepts (body 0) and a load table's
/// driver replaced alike: for checking the element's
/// own values before the others it names exist (`compile/element.rs`).
pub fn placeholders(group: &str, entry: &Value) -> Value {
    let mut e = entry.clone();
    let fields = body_fields(group, entry);
    if let Some(map) = e.as_object_mut() {
        for &(key, _) in fields {
            if map.contains_key(key) && !(key == "reaction" && map[key].is_null()) {
                map.insert(key.into(), Value::from(0)); // body 0: read as a body wherever one may stand
            }
        }
        for key in PROFILES {
            if let Some(argument) = map.get_mut(key).and_then(|p| p.get_mut("argument")).and_then(Value::as_object_mut) {
                if argument.get("kind").and_then(Value::as_str) == Some("angle") {
                    argument.remove("driver");
                    argument.insert("body".into(), Value::from(0));
                }
            }
        }
        if let Some(law) = map.get_mut("law").and_then(Value::as_object_mut) {
            if law.get("angle0").is_some_and(Value::is_null) {
                law.insert("angle0".into(), Value::from(0.0));
            }
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::{resolve, unresolve};
    use crate::error::Error;

    fn described() -> serde_json::Value {
        json!({
            "bodies": [{"name": "crank", "mass": 1.0, "inertia": 1e-3, "position": [0.0, 0.0], "angle": 0.7},
                       {"name": "rod", "mass": 1.0, "inertia": 1e-3, "position": [0.1, 0.0]}],
            "joints": [{"kind": "revolute", "name": "A", "body_a": "ground", "point_a": [0.0, 0.0], "body_b": "crank", "point_b": [0.0, 0.0]}],
            "drivers": [{"name": "d", "body": "crank", "law": {"kind": "constant_speed", "omega": 1.0, "angle0": null}}],
            "forces": [{"kind": "force", "name": "gas", "body": "rod", "point": [0.0, 0.0], "frame": "global",
                        "fx": {"kind": "table", "argument": {"kind": "angle", "driver": "d"}, "table": {"x": [0.0, 1.0], "y": [0.0, 1.0]}},
                        "fy": {"kind": "constant", "value": 0.0}},
                       {"kind": "torque", "name": "t", "body": "rod", "reaction": null, "magnitude": {"kind": "constant", "value": 1.0}}],
        })
    }

    #[test]
    fn names_become_indices_and_back() {
        let mut v = described();
        resolve(&mut v).unwrap();
        assert_eq!(v["joints"][0]["body_a"], json!(null));
        assert_eq!(v["joints"][0]["body_b"], json!(0));
        assert_eq!(v["drivers"][0]["law"]["angle0"], json!(0.7)); // the body's angle
        assert_eq!(v["forces"][0]["fx"]["argument"], json!({"kind": "angle", "body": 0})); // the driver's body
        assert_eq!(v["forces"][1]["reaction"], json!(null));
        let again = v.clone();
        resolve(&mut v).unwrap(); // indices stay as they are
        assert_eq!(v, again);
        unresolve(&mut v);
        assert_eq!(v["joints"][0]["body_a"], json!("ground"));
        assert_eq!(v["forces"][0]["fx"]["argument"]["body"], json!("crank"));
        assert_eq!(v["forces"][1]["reaction"], json!(null));
    }

    #[test]
    fn an_unknown_name_names_the_element_and_its_field() {
        let mut v = described();
        v["joints"][0]["body_b"] = json!("crnak");
        match resolve(&mut v) {
            Err(Error::InvalidInput { field, value, reason }) => {
                assert_eq!(field, "joint 'A'.body_b");
                assert_eq!(value, "'crnak'");
                assert_eq!(reason, "no such body (known: ground, crank, rod)");
            }
            other => panic!("{other:?}"),
        }
        let mut v = described();
        v["forces"][0]["fx"]["argument"]["driver"] = json!("drive9");
        let e = resolve(&mut v).unwrap_err();
        assert_eq!(e.to_string(), "invalid force 'gas'.value.driver = 'drive9': no such driver or motor (known: d)");
        let mut v = described();
        v["drivers"][0]["body"] = json!("ground");
        let e = resolve(&mut v).unwrap_err();
        assert_eq!(e.to_string(), "invalid driver 'd'.body = 'ground': the ground cannot be driven or slide (known: crank, rod)");
    }
}
