//! Self-collision settings from Python: a bool or a scene's `[self_collision]` keys.

use crate::convert::from_dict;
use crate::errors::input;
use pyo3::prelude::*;

/// Self-collision from Python: None or True, the default; False, off; or a scene's
/// `[self_collision]` keys.
pub fn self_collision_of(value: Option<&Bound<'_, PyAny>>) -> PyResult<cloth::SelfCollision> {
    match value {
        None => Ok(cloth::SelfCollision::default()),
        Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => Ok(if v.extract::<bool>()? {
            cloth::SelfCollision::default()
        } else {
            cloth::SelfCollision::off()
        }),
        Some(v) => {
            let s: cloth::SelfCollision = from_dict(v, "self_collision")?;
            s.validate().map_err(input)?;
            Ok(s)
        }
    }
}
