//! What a newcomer meant: the keys and names other tools (and textbooks) use, mapped to the
//! language's, so that an unknown key or name says what to write instead.

/// Keys other tools use, per attribute (`"*"`: any body attribute), and the key meant.
const KEY_SYNONYMS: &[(&str, &str, &str)] = &[
    ("*", "m", "mass"),
    ("*", "i", "inertia"),
    ("*", "j", "inertia"),
    ("*", "moment_of_inertia", "inertia"),
    ("*", "pos", "at"),
    ("*", "position", "at"),
    ("*", "theta", "angle"),
    ("*", "phi", "angle"),
    ("*", "orientation", "angle"),
    ("spring", "stiffness", "k"),
    ("spring", "rest_length", "length"),
    ("spring", "free_length", "length"),
    ("spring", "natural_length", "length"),
    ("spring", "l0", "length"),
    ("damper", "damping", "c"),
    ("damper", "b", "c"),
    ("force", "on", "at"),
    ("force", "point", "at"),
    ("force", "force", "value"),
    ("torque", "body", "on"),
    ("torque", "torque", "value"),
    ("torque", "moment", "value"),
    ("generalized_force", "on", "along"),
    ("generalized_force", "coordinate", "along"),
    ("generalized_force", "force", "value"),
];

/// The hint for an unknown `key` in `attr` (whose keys are `allowed`), and the keys it stands
/// for (their own "has no `..`" errors would repeat it).
pub fn unknown_key(attr: &str, key: &str, allowed: &[&str]) -> (String, Vec<String>) {
    // A spring or damper acts between two points; on a coordinate it is another attribute.
    if matches!(attr, "spring" | "damper") && matches!(key, "on" | "along") {
        let law = if attr == "spring" {
            "`#[potential(0.5 * k * q * q)]` (or `k * (q - q0)` in a `generalized_force`)"
        } else {
            "`#[generalized_force(name, along = q, value = -c * der(q))]`"
        };
        return (
            format!(
                ": a {attr} acts along the line between two points, `from = ..` and `to = ..`; \
                 a torsional {attr} on a coordinate `q` (a joint's angle) is {law}"
            ),
            vec!["from".into(), "to".into()],
        );
    }
    let meant = KEY_SYNONYMS
        .iter()
        .find(|(a, wrong, right)| {
            (*a == attr || *a == "*") && *wrong == key && allowed.contains(right)
        })
        .map(|&(_, _, right)| right)
        .or_else(|| crate::lower::closest(key, allowed.iter().copied()));
    match meant {
        Some(right) => (format!(": write `{right} = ..`"), vec![right.to_string()]),
        None => (String::new(), Vec::new()),
    }
}

/// `der(base)` where `name` is a rate spelled as other tools do (`dth`, `thd`, `th_d`,
/// `thdot`, `th_rate`) of a declared `base`.
pub fn rate(name: &str, declared: &[&str]) -> Option<String> {
    const PREFIXES: &[&str] = &["d_", "d", "dot_"];
    const SUFFIXES: &[&str] = &["_dot", "dot", "_d", "d", "_rate", "_t", "_prime", "p"];
    let from_prefix = PREFIXES.iter().filter_map(|p| name.strip_prefix(p));
    let from_suffix = SUFFIXES.iter().filter_map(|s| name.strip_suffix(s));
    from_prefix
        .chain(from_suffix)
        .find(|base| !base.is_empty() && declared.contains(base))
        .map(|base| format!("der({base})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_of_other_tools_are_mapped() {
        let spring = ["from", "to", "k", "length"];
        assert_eq!(unknown_key("spring", "rest_length", &spring).1, ["length"]);
        assert_eq!(unknown_key("spring", "stiffness", &spring).1, ["k"]);
        assert_eq!(unknown_key("spring", "lenght", &spring).1, ["length"]);
        assert_eq!(unknown_key("spring", "on", &spring).1, ["from", "to"]);
        assert_eq!(unknown_key("particle", "m", &["mass", "at"]).1, ["mass"]);
        // `angle` is not a key of a particle: no hint towards it.
        assert!(
            unknown_key("particle", "theta", &["mass", "at"])
                .1
                .is_empty()
        );
        assert!(
            unknown_key("particle", "color", &["mass", "at"])
                .0
                .is_empty()
        );
    }

    #[test]
    fn rates_are_recognised_only_of_declared_names() {
        let declared = ["th", "x", "m"];
        assert_eq!(rate("dth", &declared).as_deref(), Some("der(th)"));
        assert_eq!(rate("thd", &declared).as_deref(), Some("der(th)"));
        assert_eq!(rate("x_dot", &declared).as_deref(), Some("der(x)"));
        assert_eq!(rate("thdot", &declared).as_deref(), Some("der(th)"));
        assert_eq!(rate("bound", &declared), None);
        assert_eq!(rate("d", &declared), None);
    }
}
