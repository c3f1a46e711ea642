//! Run-time side of minimal coordinates for closed loops: the closed form of a dependent
//! coordinate (an `asin` or `acos` the derive wrote) is only valid strictly inside its
//! domain. Outside it the loop cannot assemble; at its edge two assembly branches meet (a
//! toggle or limit position) and the closed form could not tell which one the motion
//! continues on. Either way the generated code stops with [`Error::SingularPosition`]
//! rather than pass a NaN on or switch branch silently.

use crate::error::{Error, Result};

/// `Ok` when `-1 < arg < 1`; else the error naming `coord`, the time and the configuration
/// (`names[i] = q[i]`).
#[inline]
pub fn check_domain(t: f64, arg: f64, coord: &str, names: &[&str], q: &[f64]) -> Result<()> {
    if arg > -1.0 && arg < 1.0 {
        Ok(())
    } else {
        Err(singular(t, arg, coord, names, q))
    }
}

#[cold]
fn singular(t: f64, arg: f64, coord: &str, names: &[&str], q: &[f64]) -> Error {
    let config: Vec<String> = names
        .iter()
        .zip(q)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    Error::SingularPosition {
        t,
        detail: format!(
            "the closed form of `{coord}` needs an asin/acos argument strictly inside (-1, 1), got {arg} at {}: the loop cannot assemble there or is at a toggle (limit) position",
            config.join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_passes_and_the_edge_and_outside_fail() {
        assert!(check_domain(0.0, 0.5, "x", &["q"], &[1.0]).is_ok());
        for bad in [1.0, -1.0, 1.5, f64::NAN, f64::INFINITY] {
            match check_domain(2.5, bad, "beta", &["theta"], &[0.25]) {
                Err(Error::SingularPosition { t, detail }) => {
                    assert_eq!(t, 2.5);
                    assert!(detail.contains("`beta`") && detail.contains("theta = 0.25"));
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
    }
}
