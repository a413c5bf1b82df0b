//! Triangle's file-name rules: what the input name implies, and the iteration numbers of outputs.

/// The input file name split as Triangle reads it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputName {
    /// The name without a recognised extension: `mesh.1` for `mesh.1.ele`.
    pub base: String,
    /// Switches the extension implies: `p` for `.poly`, `r` for `.ele`, `ra` for `.area`.
    pub implied_switches: &'static str,
}

/// Splits `name` into its base and the switches its extension implies (`.node` implies none; any
/// other name is a base name as it is).
pub fn split_input_name(name: &str) -> InputName {
    for (extension, implied_switches) in [
        (".node", ""),
        (".poly", "p"),
        (".ele", "r"),
        (".area", "ra"),
    ] {
        if let Some(base) = name.strip_suffix(extension) {
            return InputName {
                base: base.to_string(),
                implied_switches,
            };
        }
    }
    InputName {
        base: name.to_string(),
        implied_switches: "",
    }
}

/// The base name of the next iteration: `mesh.3` → `mesh.4`, and a name without an iteration
/// number (what follows its last `.` is not all digits) counts as iteration 0: `mesh` → `mesh.1`.
pub fn next_iteration_name(base: &str) -> String {
    if let Some(dot) = base.rfind('.') {
        let number = &base[dot + 1..];
        if !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()) {
            // Leading zeros are dropped (`mesh.01` → `mesh.2`); an absurdly long number saturates.
            let next = number
                .parse::<u64>()
                .map_or(u64::MAX, |n| n.saturating_add(1));
            return format!("{}.{next}", &base[..dot]);
        }
    }
    format!("{base}.1")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_imply_switches() {
        assert_eq!(
            split_input_name("a.node"),
            InputName {
                base: "a".into(),
                implied_switches: ""
            }
        );
        assert_eq!(
            split_input_name("d/a.1.poly"),
            InputName {
                base: "d/a.1".into(),
                implied_switches: "p"
            }
        );
        assert_eq!(split_input_name("a.1.ele").implied_switches, "r");
        assert_eq!(split_input_name("a.1.area").implied_switches, "ra");
        assert_eq!(
            split_input_name("a.1"),
            InputName {
                base: "a.1".into(),
                implied_switches: ""
            }
        );
    }

    /// The cases were checked against Debian's `triangle`.
    #[test]
    fn iteration_numbers_as_triangle() {
        assert_eq!(next_iteration_name("a"), "a.1");
        assert_eq!(next_iteration_name("a.1"), "a.2");
        assert_eq!(next_iteration_name("a.9"), "a.10");
        assert_eq!(next_iteration_name("a.01"), "a.2");
        assert_eq!(next_iteration_name("a.b"), "a.b.1");
        assert_eq!(next_iteration_name("a.1x"), "a.1x.1");
        assert_eq!(next_iteration_name("a..3"), "a..4");
        assert_eq!(next_iteration_name("a.-1"), "a.-1.1");
        assert_eq!(next_iteration_name("a."), "a..1");
        assert_eq!(next_iteration_name("d.3/x"), "d.3/x.1");
    }
}
