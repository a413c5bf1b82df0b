//! Plain data at the boundary of the safe engine: what a caller gives ([`Input`]), what the engine
//! returns ([`Output`], [`VoronoiOutput`]) and the per-call hooks ([`Hooks`]).
//!
//! Arrays are flat and row-major exactly as in Triangle's `struct triangulateio` (item `i` of width
//! `w` at `[i*w .. i*w+w]`), and indices are in the caller's numbering (1-based unless `z`), so the
//! C edge and the file readers and writers convert without reshaping.

/// The caller's input, borrowed. Empty slices stand for NULL arrays.
#[derive(Clone, Copy, Debug, Default)]
pub struct Input<'a> {
    /// x, y per point.
    pub points: &'a [f64],
    /// `point_attribute_count` values per point.
    pub point_attributes: &'a [f64],
    pub point_attribute_count: usize,
    /// One marker per point, or `None` (all zero).
    pub point_markers: Option<&'a [i32]>,
    /// `corners` vertex indices per triangle (`r`).
    pub triangles: &'a [i32],
    pub corners: usize,
    /// `triangle_attribute_count` values per triangle (`r`).
    pub triangle_attributes: &'a [f64],
    pub triangle_attribute_count: usize,
    /// One maximum area per triangle (`r` with `a`), or `None`.
    pub triangle_areas: Option<&'a [f64]>,
    /// Two vertex indices per segment.
    pub segments: &'a [i32],
    /// One marker per segment, or `None` (all zero).
    pub segment_markers: Option<&'a [i32]>,
    /// x, y per hole.
    pub holes: &'a [f64],
    /// x, y, attribute, maximum area per region.
    pub regions: &'a [f64],
}

impl Input<'_> {
    pub fn point_count(&self) -> usize {
        self.points.len() / 2
    }
    pub fn triangle_count(&self) -> usize {
        self.triangles.len().checked_div(self.corners).unwrap_or(0)
    }
    pub fn segment_count(&self) -> usize {
        self.segments.len() / 2
    }
    pub fn hole_count(&self) -> usize {
        self.holes.len() / 2
    }
    pub fn region_count(&self) -> usize {
        self.regions.len() / 4
    }
}

/// What the engine produced. `None` means "not written" (the switch that asks for it is absent,
/// or a suppressing switch is present); the counts are always set, as Triangle sets them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Output {
    pub point_count: usize,
    pub point_attribute_count: usize,
    pub points: Option<Vec<f64>>,
    pub point_attributes: Option<Vec<f64>>,
    pub point_markers: Option<Vec<i32>>,

    pub triangle_count: usize,
    /// 3, or 6 with `o2`.
    pub corners: usize,
    pub triangle_attribute_count: usize,
    pub triangles: Option<Vec<i32>>,
    pub triangle_attributes: Option<Vec<f64>>,
    pub neighbors: Option<Vec<i32>>,

    pub segment_count: usize,
    pub segments: Option<Vec<i32>>,
    pub segment_markers: Option<Vec<i32>>,

    /// Holes and regions are not copied: with `p` (and not `P`) the output aliases the input's
    /// arrays, as Triangle does. These say how many items the aliases have.
    pub hole_count: usize,
    pub region_count: usize,
    pub alias_holes_and_regions: bool,

    pub edge_count: usize,
    pub edges: Option<Vec<i32>>,
    pub edge_markers: Option<Vec<i32>>,

    /// Warnings (duplicate vertices, skipped segments, a failed `C` check, …), printed by the
    /// edge unless `Q`.
    pub warnings: Vec<String>,
    /// `C`: what the check of the final mesh found (`None` without `C`). A mesh that passes is
    /// a result, not a warning; one that fails is among the warnings too.
    pub mesh_check: Option<MeshCheck>,
}

/// What `C`'s check of the final mesh found: whether the triangles fit together, face the same
/// way and are (constrained) Delaunay, each judged with exact arithmetic.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshCheck {
    /// Consistent, and no edge but a segment fails the in-circle test.
    Passed,
    /// The triangles do not fit together (why).
    Inconsistent(String),
    /// The triangles fit together, but `inverted` of them are inverted or flat and
    /// `not_delaunay` edges (segments aside) are not locally Delaunay.
    Failed {
        inverted: usize,
        not_delaunay: usize,
    },
}

impl MeshCheck {
    /// The warning a failed check gives (`None` when it passed).
    pub fn warning(&self) -> Option<String> {
        match self {
            MeshCheck::Passed => None,
            MeshCheck::Inconsistent(why) => {
                Some(format!("Mesh check: the topology is inconsistent: {why}."))
            }
            MeshCheck::Failed {
                inverted,
                not_delaunay,
            } => Some(format!(
                "Mesh check: {inverted} triangles are inverted or flat and {not_delaunay} edges are not locally Delaunay."
            )),
        }
    }

    /// The report as Triangle prints it after its statistics: a line on the consistency of the
    /// mesh and one on its Delaunay property, each after the line that announces it (Triangle's
    /// words where the mesh passes, ours where it fails).
    pub fn report(&self) -> Vec<String> {
        const CONSISTENT: &str = "In my studied opinion, the mesh appears to be consistent.";
        const DELAUNAY: &str =
            "By virtue of my perceptive intelligence, I declare the mesh Delaunay.";
        let (consistency, delaunay) = match self {
            MeshCheck::Passed => (CONSISTENT.to_string(), Some(DELAUNAY.to_string())),
            MeshCheck::Inconsistent(why) => (format!("The topology is inconsistent: {why}."), None),
            MeshCheck::Failed {
                inverted,
                not_delaunay,
            } => (
                match inverted {
                    0 => CONSISTENT.to_string(),
                    n => format!("{n} triangles are inverted or flat."),
                },
                Some(match not_delaunay {
                    0 => DELAUNAY.to_string(),
                    n => format!("{n} edges are not locally Delaunay."),
                }),
            ),
        };
        let mut lines = vec!["Checking consistency of mesh...".to_string(), consistency];
        if let Some(delaunay) = delaunay {
            lines.push("Checking Delaunay property of mesh...".to_string());
            lines.push(delaunay);
        }
        lines
    }
}

/// The Voronoi diagram (`v`). Counts are set even without `v` (Triangle does so when `vorout`
/// is given); the arrays only with `v`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VoronoiOutput {
    pub point_count: usize,
    pub point_attribute_count: usize,
    pub edge_count: usize,
    /// Present only with `v`.
    pub diagram: Option<VoronoiDiagram>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct VoronoiDiagram {
    /// One circumcentre per triangle (x, y), in output triangle order.
    pub points: Vec<f64>,
    /// Attributes interpolated at each circumcentre.
    pub point_attributes: Vec<f64>,
    /// Two indices per edge (caller's numbering); the second is −1 for a ray.
    pub edges: Vec<i32>,
    /// Ray directions; (0, 0) for finite edges.
    pub norms: Vec<f64>,
}

/// The user's refinement test (`u`): arguments are org x, y, dest x, y, apex x, y and area;
/// `true` means the triangle is unsuitable and must be split.
pub type UnsuitableFn<'a> = dyn Fn(f64, f64, f64, f64, f64, f64, f64) -> bool + Sync + 'a;

/// A phase of a call, in the order they run (the numbers are the C ABI's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Building the Delaunay triangulation of the vertices (or the mesh given with `r`).
    Delaunay = 0,
    /// Inserting segments (`p`, `c`).
    Segments = 1,
    /// Delaunay refinement (`q`, `a`, `u`, `D`).
    Refinement = 2,
    /// Numbering and writing the outputs.
    Output = 3,
}

/// What a call reports of its progress: the phase, the work done in it, and an estimate of the
/// phase's total (0 when unknown). For refinement, the work is the vertices inserted (above
/// 28.6°, in all the runs it tries, including meshes it then discards), and the estimate those
/// plus the bad triangles and encroached segments waiting: it grows as
/// refinement finds more work, and meets the count at the end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub phase: Phase,
    pub done: u64,
    pub estimate: u64,
}

/// The progress callback: called at the start and end of each phase, and during long phases
/// where the cancel flag is polled.
pub type ProgressFn<'a> = dyn Fn(Progress) + Sync + 'a;

/// Per-call hooks: no global state.
#[derive(Clone, Copy, Default)]
pub struct Hooks<'a> {
    /// The test of `u`; `None`: Triangle's built-in test
    /// ([`crate::algorithms::refine::builtin_unsuitable`]).
    pub unsuitable: Option<&'a UnsuitableFn<'a>>,
    /// Polled during long work; `true` stops refinement early with a valid mesh.
    pub cancel: Option<&'a (dyn Fn() -> bool + Sync + 'a)>,
    /// Told of the call's progress (see [`Progress`]).
    pub progress: Option<&'a ProgressFn<'a>>,
}

impl Hooks<'_> {
    /// Reports progress, if the caller asked for it.
    pub fn report(&self, phase: Phase, done: u64, estimate: u64) {
        if let Some(progress) = self.progress {
            progress(Progress {
                phase,
                done,
                estimate,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_check_reports_as_triangle_and_warns_only_when_failed() {
        assert_eq!(MeshCheck::Passed.warning(), None);
        assert_eq!(
            MeshCheck::Passed.report(),
            [
                "Checking consistency of mesh...",
                "In my studied opinion, the mesh appears to be consistent.",
                "Checking Delaunay property of mesh...",
                "By virtue of my perceptive intelligence, I declare the mesh Delaunay.",
            ]
        );
        let failed = MeshCheck::Failed {
            inverted: 0,
            not_delaunay: 2,
        };
        assert_eq!(
            failed.warning().as_deref(),
            Some("Mesh check: 0 triangles are inverted or flat and 2 edges are not locally Delaunay.")
        );
        let report = failed.report();
        assert_eq!(
            report[1],
            "In my studied opinion, the mesh appears to be consistent."
        );
        assert_eq!(report[3], "2 edges are not locally Delaunay.");
        let inconsistent = MeshCheck::Inconsistent("edge 3 has no twin".into());
        assert!(inconsistent
            .warning()
            .unwrap()
            .contains("edge 3 has no twin"));
        assert_eq!(inconsistent.report().len(), 2);
    }
}
