//! The error of a parameter out of its range, which every module may refuse.

use thiserror::Error;

/// A physical or numerical parameter that is out of its valid range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParamError {
    #[error("parameter `{name}` = {value} is invalid: {expected}")]
    OutOfRange {
        name: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error("parameter `{name}` = {value} is inconsistent: {reason}")]
    Inconsistent {
        name: &'static str,
        value: f64,
        reason: String,
    },
    #[error("tensile curve `{name}` is invalid: {reason}")]
    BadCurve { name: &'static str, reason: String },
    #[error("pin on particle {particle}, but the mesh has {count} particles")]
    PinOutOfRange { particle: usize, count: usize },
}

impl ParamError {
    /// `Ok` when `ok`, otherwise the out-of-range error for `name`.
    pub fn check(ok: bool, name: &'static str, value: f64, expected: &'static str) -> Result<(), Self> {
        if ok {
            Ok(())
        } else {
            Err(Self::OutOfRange {
                name,
                value,
                expected,
            })
        }
    }
}
