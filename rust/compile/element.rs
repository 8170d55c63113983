//! One element checked alone, as it is added (`Mechanism.add_body`, `Dry(...)`, ...): its own
//! values, with the same checks and messages as the whole description's ([`super::validate`]:
//! one validator). Its references to other elements (bodies, drivers) are left to the compile,
//! so elements may still be defined in any order.

use serde::de::DeserializeOwned;
use serde_json::Value;

use crate::names::placeholders;
use super::validate;
use crate::error::{Error, Result};

/// Check one element of the description list `group` (`"bodies"`, `"joints"`, `"drivers"`,
/// `"clearance_joints"`, `"prismatic_clearance_joints"`, `"forces"`) or a clearance model alone
/// (`"dry"`, `"lubricated"`: its fields named without an owner, `viscosity`), given as plain
/// data with its references by name.
pub fn check_element(group: &str, entry: &Value) -> Result<()> {
    let value = placeholders(group, entry);
    if matches!(group, "dry" | "lubricated") {
        return unowned(match group {
            "dry" => validate::validate_dry("", &model(group, entry, value)?),
            _ => validate::lubricated("", &model(group, entry, value)?),
        });
    }
    // Read as the one element of a description: serde's errors are named as a description's are
    // (`body 'crank'.mass`, `force 'f'.frame`).
    let mut root = serde_json::Map::new();
    root.insert(group.to_string(), Value::Array(vec![value]));
    let desc = crate::description::from_value(Value::Object(root))?;
    match group {
        "bodies" => validate::body(&desc.bodies[0]),
        "joints" => validate::joint(&desc.joints[0]),
        "drivers" => validate::driver(&desc.drivers[0]),
        "clearance_joints" => validate::clearance_joint(&desc.clearance_joints[0]),
        "prismatic_clearance_joints" => validate::prismatic_clearance(&desc.prismatic_clearance_joints[0]),
        "forces" => validate::force(&desc.forces[0]),
        other => Err(Error::invalid("group", super::quoted(other), "must be one of bodies, joints, drivers, clearance_joints, prismatic_clearance_joints, forces, dry, lubricated")),
    }
}

/// A clearance model alone, or the deserialisation error naming its field (`film`).
fn model<T: DeserializeOwned>(group: &str, entry: &Value, value: Value) -> Result<T> {
    serde_path_to_error::deserialize::<_, T>(value).map_err(|e| {
        let path = e.path().to_string();
        let field = if path == "." { group.to_string() } else { path };
        let at = e.path().iter().try_fold(entry, |v, seg| match seg {
            serde_path_to_error::Segment::Map { key } => v.get(key.as_str()),
            serde_path_to_error::Segment::Seq { index } => v.get(*index),
            _ => Some(v),
        });
        let value = at.map_or_else(|| "(missing)".to_string(), |v| v.as_str().map_or_else(|| v.to_string(), super::quoted));
        Error::invalid(field, value, e.inner().to_string())
    })
}

/// A model's error with its fields named without an owner: `.viscosity` → `viscosity`.
fn unowned(r: Result<()>) -> Result<()> {
    r.map_err(|e| match e {
        Error::InvalidInput { field, value, reason } => Error::InvalidInput { field: field.trim_start_matches('.').to_string(), value, reason },
        other => other,
    })
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::check_element;
    use crate::error::Error;

    fn field(r: crate::error::Result<()>) -> String {
        match r {
            Err(Error::InvalidInput { field, .. }) => field,
            other => panic!("expected an InvalidInput, got {other:?}"),
        }
    }

    #[test]
    fn an_element_is_checked_alone_with_the_compile_s_messages() {
        let body = json!({"name": "crank", "mass": -1.0, "inertia": 1e-3, "position": [0.0, 0.0]});
        assert_eq!(field(check_element("bodies", &body)), "body 'crank'.mass");
        let ok = json!({"name": "crank", "mass": 1.0, "inertia": 1e-3, "position": [0.0, 0.0]});
        assert!(check_element("bodies", &ok).is_ok());
        // References by name to elements that do not exist yet are the compile's to check.
        let joint = json!({"kind": "revolute", "name": "A", "body_a": "ground", "point_a": [0.0, 0.0], "body_b": "not yet", "point_b": [0.1, 0.0]});
        assert!(check_element("joints", &joint).is_ok());
        let lub = json!({"viscosity": -0.1, "length": 0.02});
        let e = check_element("lubricated", &lub).unwrap_err();
        assert_eq!(e.to_string(), "invalid viscosity = -0.1: must be positive");
        let cj = json!({"name": "B", "bearing_body": "rod", "bearing_point": [0.0, 0.0], "journal_body": "slider", "journal_point": [0.0, 0.0],
                        "journal_radius": 0.01, "clearance": -1e-3, "model": {"kind": "dry"}});
        assert_eq!(field(check_element("clearance_joints", &cj)), "clearance joint 'B'.clearance");
    }
}
