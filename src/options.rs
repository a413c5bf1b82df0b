//! Triangle's switch string, parsed once into a typed [`Options`].
//!
//! The engine never sees the string. Parsing follows Triangle 1.6 (`parsecommandline`): the string is
//! scanned one character at a time, unknown characters are ignored, and `q`, `a` and `S` may be
//! followed by a number. Two deliberate improvements, documented in README.md:
//! - exponent notation after a number (`a1e-5`, `q2.5e1`): a lowercase `e` directly after a number is
//!   an exponent when it is followed by a digit, or by a sign and a digit; otherwise it is the `e`
//!   switch. An uppercase `E` is never an exponent: it is the `E` switch, as in Triangle (`a2E-1` is
//!   `a2` and `E`; the `-` and `1` are ignored);
//! - numbers are parsed without the C locale (Triangle uses `strtod`, which obeys `LC_NUMERIC`).
//!
//! And one switch of ours, a letter Triangle ignores: `R`, reduce the refined mesh (decimation
//! and polish after refinement: fewer triangles, more time; see `algorithms::refine`).

use crate::error::Error;

/// Which algorithm builds the Delaunay triangulation of the vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Algorithm {
    /// The default: the fastest builder (insertion in Hilbert-curve order).
    #[default]
    Default,
    /// `i`: randomized incremental insertion (biased randomized insertion order) with Lawson flips.
    Incremental,
    /// `F`: Triangle's sweepline; accepted, served by the default builder (same triangle set).
    Sweepline,
}

/// Where a switch string comes from: the library ignores `I` and `h`, as Triangle's does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwitchSource {
    Library,
    CommandLine,
}

/// Parsed switches. Field names follow what the switch does, with the letter in the doc comment.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Options {
    /// `p`: triangulate a planar straight line graph (segments, holes, regions).
    pub pslg: bool,
    /// `r`: refine a previously generated mesh.
    pub refine: bool,
    /// `q`: minimum angle in degrees (`q` alone: 20).
    pub min_angle: Option<f64>,
    /// `a<x>`: global maximum triangle area.
    pub max_area: Option<f64>,
    /// `a` without a number: regional (`p`) or per-triangle (`r`) area constraints.
    pub variable_area: bool,
    /// `u`: the user's `triunsuitable` test (Triangle's built-in one when none is registered).
    pub user_test: bool,
    /// `A`: regional attributes appended to the triangle attributes.
    pub region_attributes: bool,
    /// `c`: enclose the convex hull with segments.
    pub convex_hull: bool,
    /// `D` (or `L`): conforming Delaunay.
    pub conforming_delaunay: bool,
    /// `j`: jettison vertices that are not part of the final mesh.
    pub jettison: bool,
    /// `O`: ignore holes.
    pub ignore_holes: bool,
    /// `X`: no exact arithmetic.
    pub no_exact: bool,
    /// `z`: number everything from zero.
    pub zero_based: bool,
    /// `o2`: second-order (6-node) triangles.
    pub second_order: bool,
    /// `Y` (1) / `YY` (2): no Steiner points on boundary segments / on any segment.
    pub no_steiner_on_segments: u8,
    /// `S<n>`: maximum number of Steiner points (`S` alone: 0).
    pub max_steiner: Option<u64>,
    /// `R` (ours; Triangle ignores it): reduce the refined mesh — decimate and polish it after
    /// refinement, for fewer triangles (0.65–0.86× Triangle's) at a few times the time.
    pub reduce: bool,
    /// `i`, `F`: the Delaunay algorithm.
    pub algorithm: Algorithm,
    /// `l`: only vertical cuts in divide and conquer (accepted; no effect on the result).
    pub vertical_cuts_only: bool,
    /// `s`: insert segments by splitting instead of CDT.
    pub split_segments: bool,
    /// `C`: check the final mesh and report.
    pub check: bool,
    /// `Q`: quiet.
    pub quiet: bool,
    /// `V`: verbosity (number of `V`s).
    pub verbose: u8,
    /// `h`: print the full instructions (command line only).
    pub help: bool,
    /// `w` (1) or `W` (2): weighted / regular triangulation (parsed; not supported yet).
    pub weighted: u8,
    /// What to write: the output arrays and files (`e`, `v`, `n`, `g`, `B`, `P`, `N`, `E`, `I`).
    pub output: OutputOptions,
}

/// The switches that choose what is written rather than what is computed: extra outputs (edges,
/// Voronoi diagram, neighbours, the `.off` file) and outputs left out (markers, segments,
/// vertices, triangles, iteration numbers). The command-line program computes everything and
/// applies the suppressions when writing files; the C ABI applies them to the output struct.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct OutputOptions {
    /// `e`: output the edge list.
    pub edges: bool,
    /// `v`: output the Voronoi diagram.
    pub voronoi: bool,
    /// `n`: output triangle neighbours.
    pub neighbors: bool,
    /// `g`: write a Geomview `.off` file (command line only).
    pub geomview: bool,
    /// `B`: no boundary markers in the output.
    pub no_boundary_markers: bool,
    /// `P`: no output segments.
    pub no_poly_output: bool,
    /// `N`: no output vertices.
    pub no_node_output: bool,
    /// `E`: no output triangles.
    pub no_element_output: bool,
    /// `I`: no iteration numbers in file names (command line only).
    pub no_iteration_numbers: bool,
}

impl OutputOptions {
    /// The same extra outputs, with nothing left out (no `B`, `P`, `N`, `E`): what a caller that
    /// applies the suppressions itself (the command-line program, when writing files) asks of
    /// the engine.
    pub fn without_suppressions(&self) -> OutputOptions {
        OutputOptions {
            no_boundary_markers: false,
            no_poly_output: false,
            no_node_output: false,
            no_element_output: false,
            ..self.clone()
        }
    }
}

impl Options {
    /// Parses a switch string as Triangle does, with the improvements described in the module doc.
    pub fn parse(switches: &str, source: SwitchSource) -> Result<Options, Error> {
        let mut o = Options::default();
        let bytes = switches.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i];
            i += 1;
            match c {
                b'p' => o.pslg = true,
                b'r' => o.refine = true,
                b'q' => {
                    let (value, next) = parse_number(bytes, i);
                    i = next;
                    o.min_angle = Some(value.unwrap_or(20.0));
                }
                b'a' => {
                    let (value, next) = parse_number(bytes, i);
                    i = next;
                    match value {
                        Some(area) => o.max_area = Some(area),
                        None => o.variable_area = true,
                    }
                }
                b'u' => o.user_test = true,
                b'A' => o.region_attributes = true,
                b'c' => o.convex_hull = true,
                b'D' | b'L' => o.conforming_delaunay = true,
                b'j' => o.jettison = true,
                b'e' => o.output.edges = true,
                b'v' => o.output.voronoi = true,
                b'n' => o.output.neighbors = true,
                b'g' => o.output.geomview = true,
                b'B' => o.output.no_boundary_markers = true,
                b'P' => o.output.no_poly_output = true,
                b'N' => o.output.no_node_output = true,
                b'E' => o.output.no_element_output = true,
                b'I' if source == SwitchSource::CommandLine => o.output.no_iteration_numbers = true,
                b'h' if source == SwitchSource::CommandLine => o.help = true,
                b'O' => o.ignore_holes = true,
                b'X' => o.no_exact = true,
                b'z' => o.zero_based = true,
                b'o' if bytes.get(i) == Some(&b'2') => {
                    o.second_order = true;
                    i += 1;
                }
                b'Y' => o.no_steiner_on_segments = (o.no_steiner_on_segments + 1).min(2),
                b'S' => {
                    let (value, next) = parse_number(bytes, i);
                    i = next;
                    // Triangle reads only digits here; a fraction is truncated.
                    o.max_steiner = Some(value.map_or(0, |v| if v > 0.0 { v as u64 } else { 0 }));
                }
                b'R' => o.reduce = true,
                b'i' => o.algorithm = Algorithm::Incremental,
                b'F' => o.algorithm = Algorithm::Sweepline,
                b'l' => o.vertical_cuts_only = true,
                b's' => o.split_segments = true,
                b'C' => o.check = true,
                b'Q' => o.quiet = true,
                b'V' => o.verbose = o.verbose.saturating_add(1),
                b'w' => o.weighted = 1,
                b'W' => o.weighted = 2,
                _ => {} // Triangle ignores every other character.
            }
        }
        // Derived rules of Triangle's parsecommandline.
        if !(o.pslg || o.refine) {
            o.variable_area = false;
        }
        if o.refine || !o.pslg {
            o.region_attributes = false;
        }
        if o.pslg || o.quality() {
            o.weighted = 0;
        }
        if let Some(area) = o.max_area {
            if area.is_nan() || area <= 0.0 {
                return Err(Error::NonPositiveMaxArea);
            }
        }
        if o.min_angle.is_some_and(|angle| !angle.is_finite()) {
            // Only an exponent can overflow (`q1e999`): no angle means that.
            return Err(Error::NonFiniteMinAngle);
        }
        Ok(o)
    }

    /// Quality refinement is on (`q`, `a`, `u` or `D`).
    pub fn quality(&self) -> bool {
        self.min_angle.is_some()
            || self.max_area.is_some()
            || self.variable_area
            || self.user_test
            || self.conforming_delaunay
    }

    /// Segments take part in the triangulation (Triangle's `usesegments`).
    pub fn uses_segments(&self) -> bool {
        self.pslg || self.refine || self.quality() || self.convex_hull
    }

    /// Index base of every vertex index in input and output: 0 with `z`, else 1.
    pub fn first_index(&self) -> i32 {
        if self.zero_based {
            0
        } else {
            1
        }
    }
}

/// Reads the number that may follow a switch at `bytes[start..]`: the longest run of digits and
/// dots (Triangle's rule; its longest valid decimal prefix is the value, `.` alone is 0), then an
/// optional exponent: a lowercase `e` and digits, or `e`, a sign and digits (an uppercase `E` is the
/// switch, as Triangle reads it). Returns `None` when no number follows, and the index after what
/// was consumed.
fn parse_number(bytes: &[u8], start: usize) -> (Option<f64>, usize) {
    let mut end = start;
    while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b'.') {
        end += 1;
    }
    if end == start {
        return (None, start);
    }
    let run = &bytes[start..end];
    // Longest prefix of the form digits [. digits].
    let first_dot = run.iter().position(|&b| b == b'.');
    let prefix_len = match first_dot {
        Some(d) => {
            d + 1
                + run[d + 1..]
                    .iter()
                    .take_while(|b| b.is_ascii_digit())
                    .count()
        }
        None => run.len(),
    };
    let whole_run_is_decimal = prefix_len == run.len();
    let mut text: String = run[..prefix_len].iter().map(|&b| b as char).collect();
    if whole_run_is_decimal && bytes.get(end) == Some(&b'e') {
        let mut k = end + 1;
        let mut exponent = String::from("e");
        if k < bytes.len() && (bytes[k] == b'+' || bytes[k] == b'-') {
            exponent.push(bytes[k] as char);
            k += 1;
        }
        let digits_start = k;
        while k < bytes.len() && bytes[k].is_ascii_digit() {
            exponent.push(bytes[k] as char);
            k += 1;
        }
        if k > digits_start {
            text.push_str(&exponent);
            end = k;
        }
    }
    // Rust's float parser is locale-independent; "." or "" (no digits) reads as 0 like strtod.
    let mantissa_has_digit = text
        .bytes()
        .take_while(|&b| b != b'e')
        .any(|b| b.is_ascii_digit());
    let value = if mantissa_has_digit {
        let normalized = if text.starts_with('.') {
            format!("0{text}")
        } else {
            text
        };
        normalized
            .replace(".e", ".0e")
            .parse::<f64>()
            .unwrap_or(0.0)
    } else {
        0.0
    };
    (Some(value), end)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lib(s: &str) -> Options {
        Options::parse(s, SwitchSource::Library).unwrap()
    }

    #[test]
    fn numbers_follow_triangle() {
        assert_eq!(lib("pq").min_angle, Some(20.0));
        assert_eq!(lib("pq33.5").min_angle, Some(33.5));
        assert_eq!(lib("pq1.2.3").min_angle, Some(1.2));
        assert_eq!(lib("pa.5").max_area, Some(0.5));
        assert!(lib("pa").variable_area);
        let o = lib("paa0.5");
        assert!(o.variable_area && o.max_area == Some(0.5));
        assert_eq!(lib("S").max_steiner, Some(0));
        assert_eq!(lib("S50").max_steiner, Some(50));
    }

    #[test]
    fn reduce_is_our_switch_and_off_by_default() {
        assert!(!lib("pq30a0.1").reduce);
        let o = lib("pq30Ra0.1");
        assert!(o.reduce);
        assert_eq!((o.min_angle, o.max_area), (Some(30.0), Some(0.1)));
    }

    #[test]
    fn exponent_notation_is_an_improvement() {
        let o = lib("pa1e-5");
        assert_eq!(o.max_area, Some(1e-5));
        assert!(!o.output.edges);
        assert_eq!(lib("q2.5e1").min_angle, Some(25.0));
        // An `e` not followed by a digit (or sign and digit) stays the edge switch.
        let o = lib("pa1e");
        assert_eq!(o.max_area, Some(1.0));
        assert!(o.output.edges);
        let o = lib("pa2e-");
        assert_eq!(o.max_area, Some(2.0));
        assert!(o.output.edges);
        let o = lib("pq30en");
        assert_eq!(o.min_angle, Some(30.0));
        assert!(o.output.edges && o.output.neighbors);
    }

    #[test]
    fn an_uppercase_e_after_a_number_is_the_e_switch() {
        // Triangle reads `a2`, then the switch `E`, and ignores `-` and `1`.
        let o = lib("pa2E-1");
        assert_eq!(o.max_area, Some(2.0));
        assert!(o.output.no_element_output && !o.output.edges);
        let o = lib("pa1E+2");
        assert_eq!(o.max_area, Some(1.0));
        assert!(o.output.no_element_output);
        let o = lib("pa0.5E3e");
        assert_eq!(o.max_area, Some(0.5));
        assert!(o.output.no_element_output && o.output.edges);
        let o = lib("pq30E1");
        assert_eq!(o.min_angle, Some(30.0));
        assert!(o.output.no_element_output);
        let o = lib("pq2.5E1");
        assert_eq!(o.min_angle, Some(2.5));
        assert!(o.output.no_element_output);
        let o = lib("pqS5E2");
        assert_eq!(o.max_steiner, Some(5));
        assert!(o.output.no_element_output);
        // Lowercase `e` keeps its rule after every number.
        assert_eq!(lib("pqS5e1").max_steiner, Some(50));
        assert_eq!(lib("pq2.5e+1").min_angle, Some(25.0));
        assert!(!lib("pq2.5e+1").output.no_element_output);
    }

    #[test]
    fn switch_letters_and_derived_rules() {
        let o = lib("Qz{pceo2YYnvBPNEIOXjs}");
        assert!(
            o.quiet && o.zero_based && o.pslg && o.convex_hull && o.output.edges && o.second_order
        );
        assert_eq!(o.no_steiner_on_segments, 2);
        assert!(
            o.output.neighbors
                && o.output.voronoi
                && o.output.no_boundary_markers
                && o.output.no_poly_output
        );
        assert!(
            o.output.no_node_output && o.output.no_element_output && o.ignore_holes && o.no_exact
        );
        assert!(o.jettison && o.split_segments);
        assert!(
            !o.output.no_iteration_numbers,
            "I is not parsed in the library"
        );
        assert!(
            Options::parse("I", SwitchSource::CommandLine)
                .unwrap()
                .output
                .no_iteration_numbers
        );
        assert!(!lib("o").second_order);
        assert!(!lib("a").variable_area, "variable area needs p or r");
        assert!(!lib("A").region_attributes, "A needs p");
        assert!(!lib("prA").region_attributes, "A is dropped with r");
        assert!(lib("pA").region_attributes);
        assert_eq!(lib("VVV").verbose, 3);
        assert_eq!(lib("i").algorithm, Algorithm::Incremental);
        assert!(lib("u").quality() && lib("D").quality() && lib("a1").quality());
        assert!(lib("c").uses_segments() && !lib("e").uses_segments());
    }

    #[test]
    fn infinite_minimum_angle_is_an_error() {
        assert_eq!(
            Options::parse("pq1e999", SwitchSource::Library),
            Err(Error::NonFiniteMinAngle)
        );
        assert_eq!(lib("pq1e1").min_angle, Some(10.0));
    }

    #[test]
    fn non_positive_area_is_an_error() {
        for s in ["a0", "a.", "pa0.0", "a0e5"] {
            assert!(matches!(
                Options::parse(s, SwitchSource::Library),
                Err(Error::NonPositiveMaxArea)
            ));
        }
    }
}
