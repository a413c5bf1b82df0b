//! The driver of a refinement: snapping, the runaway limit, the strategy above the guaranteed
//! angle with its budgets, and the report with its warnings (polling: [`super::polling`]).

use super::attributes::Attributes;
use super::encroachment::NEGLIGIBLE_SLIVER;
use super::polling::Polling;
use super::queue::QueueOrder;
use super::refinement::{Refinement, RunEnd, Settings};
use super::report::{Report, Warning};
use super::{area_bound, inside, worst_triangle, Quality, VertexKind, GUARANTEED_ANGLE};
use crate::algorithms::constrain::Constrainer;
use crate::algorithms::domain::Domain;
use crate::geometry::Predicates;
use crate::mesh::Mesh;

/// Above that angle, refinement first runs straight toward it with a budget of this many new
/// vertices per triangle of the unrefined mesh (plus what the area bound asks for); a run that
/// finishes within it stands.
const PLAIN_STRAIGHT_PER_TRIANGLE: u64 = 4;
/// If that is not enough, the straight run may go on to this many new vertices per triangle of
/// the mesh refined to the guaranteed angle.
const GUARANTEED_MULTIPLE: u64 = 4;
/// A refinement is stopped as a runaway beyond this many new vertices per triangle of the
/// unrefined mesh plus what the area bounds ask for (inputs with many tiny angles need about 100),
/// and not below this many in all (a few seconds of work).
const RUNAWAY_PER_TRIANGLE: u64 = 1000;
const RUNAWAY_MINIMUM: u64 = 1_000_000;
/// Up to this many domain triangles, the mesh before the improvement is kept aside, to
/// stand if they made it worse (a copy of the mesh, which is small then).
const GUARDED_IMPROVEMENT: u64 = 1 << 20;
/// Failing that, the mesh refined to the guaranteed angle goes on toward the asked one with a
/// budget of this many new vertices per triangle it has (plus a few).
const UNGUARANTEED_BUDGET_PER_TRIANGLE: u64 = 2;

/// Refines the domain of `cdt` (triangles outside it tagged [`OUTSIDE`](crate::mesh::OUTSIDE),
/// ghosts around it) to `quality`: until no subsegment is encroached (by diametral lenses, or
/// circles with `conforming`, `D`) and no triangle is bad, or a limit stops it. `attributes`:
/// `attribute_count` values per vertex, which new vertices get interpolated.
pub fn refine<P: Predicates>(
    cdt: &mut Constrainer<P>,
    domain: &Domain,
    quality: &Quality<'_>,
    conforming: bool,
    attributes: &mut Vec<f64>,
    attribute_count: usize,
) -> Report {
    let mesh = cdt.mesh();
    let Resolution {
        snap2,
        floor2,
        extent2,
    } = resolution(mesh);
    // Without the user's own test or budget: a run that makes far more vertices than the input
    // and the area bounds account for is stopped (an input a hair's breadth wide, such as nearly
    // collinear points with `c`, needs about length/width triangles: billions).
    let area_estimate = size_estimate::<P>(mesh, domain, quality);
    let runaway_limit = (quality.user_test.is_none() && quality.max_steiner.is_none()).then(|| {
        let expected = RUNAWAY_PER_TRIANGLE * inside_triangle_count(mesh) + area_estimate;
        expected.max(RUNAWAY_MINIMUM)
    });
    // Room for about the vertices refinement will add: an eighth of the area estimate (its
    // triangles of the bound, times four, where the lattice puts one vertex per two of them),
    // and twice as many as the input has (the meshes of the refinement benchmark's angle-only
    // rows add 0.6–4 per input vertex); never more than `S` or the runaway limit allow, nor
    // 2^22 (the arrays then grow as usual), and only where the memory is there.
    let vertices = mesh.points().len();
    let room = (area_estimate / 8)
        .saturating_add(2 * vertices as u64 + 64)
        .min(quality.max_steiner.unwrap_or(u64::MAX))
        .min(runaway_limit.unwrap_or(u64::MAX))
        .min(1 << 22) as usize;
    let mut kinds = Vec::new();
    let _ = kinds.try_reserve(vertices + room);
    kinds.resize(vertices, VertexKind::Input);
    cdt.mesh_mut().reserve_vertices(room);
    cdt.snap_vertices_onto_segments(snap2);
    domain.merge_equal_regions(cdt.mesh_mut());
    let settings = Settings {
        domain,
        quality,
        conforming,
        floor2,
        negligible_sliver: NEGLIGIBLE_SLIVER * doubled_domain_area::<P>(cdt.mesh()),
        extent2,
    };
    let refinement = Refinement::new(
        cdt,
        Attributes::new(attributes, attribute_count),
        kinds,
        settings,
        Polling::new(quality),
    );
    let mut driver = Driver {
        refinement,
        domain,
        quality,
        runaway_limit,
        warnings: Vec::new(),
    };
    let from_the_start = quality.caller_grid.is_some_and(|c| c.from_the_start);
    if from_the_start && !driver.refinement.move_onto_caller_grid() {
        return Report {
            steiner_points: 0,
            work: 0,
            warnings: Vec::new(),
            off_grid: true,
        };
    }
    let mut outcome = match quality.min_angle {
        Some(angle) if angle > GUARANTEED_ANGLE => driver.refine_beyond_the_guarantee(angle),
        _ => {
            driver.seed();
            driver.run_within(None)
        }
    };
    // With `R` the finished mesh is improved (decimated and polished: see `Driver::improve` for
    // when not), in the frame it was refined in.
    if outcome == Outcome::Finished {
        outcome = driver.improve();
    }
    // In a frame finer than the caller's: the mesh goes onto the caller's grid, and what
    // rounding spoiled there is refined again, at the angle of the last run, with new points on
    // that grid (where rounding does not cost the angle, this changes nothing).
    let mut off_grid = false;
    if quality.caller_grid.is_some() && !from_the_start && outcome == Outcome::Finished {
        if driver.refinement.move_onto_caller_grid() {
            outcome = driver.run_within(None);
        } else {
            off_grid = true;
        }
    }
    // Vertices deleted by Chew's rule and by decimation leave the numbering: Steiner points
    // stay in order after the input's.
    driver.refinement.drop_deleted_vertices();
    let tally = driver.refinement.tally();
    let mut warnings = driver.warnings;
    if outcome == Outcome::Runaway {
        warnings.push(Warning::Runaway {
            steiner_points: tally.steiner_points,
        });
    }
    // Only what the finished mesh still lacks is reported: refused splits that later ones made
    // unnecessary are not a shortfall.
    if outcome == Outcome::UserBudget {
        // The caller's own limit: said only where it left the mesh short of the bounds.
        let unmet = driver.refinement.unmet_bounds();
        if unmet > 0 {
            warnings.push(Warning::BudgetSpent {
                limit: quality.max_steiner.unwrap_or(0),
                unmet,
            });
        }
    } else if tally.skipped > 0 {
        let unsplit = driver.refinement.unmet_bounds();
        if unsplit > 0 {
            warnings.push(Warning::PrecisionExhausted { unsplit });
        }
    }
    if tally.kept_whole > 0 {
        warnings.push(Warning::SegmentsKeptWhole {
            unsplit: tally.kept_whole,
        });
    }
    Report {
        steiner_points: tally.steiner_points,
        work: driver.refinement.work(),
        warnings,
        off_grid,
    }
}

/// How a budgeted refinement run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outcome {
    /// No subsegment is encroached and no triangle is bad.
    Finished,
    Cancelled,
    /// The `S` budget is spent.
    UserBudget,
    /// The budget of the run is spent (the strategy above the guaranteed angle decides what
    /// next).
    RunBudget,
    /// The runaway limit is reached.
    Runaway,
}

struct Driver<'r, 'q, P: Predicates> {
    refinement: Refinement<'r, 'q, P>,
    domain: &'r Domain,
    quality: &'r Quality<'q>,
    /// Where any run is stopped as a runaway (see [`refine`]).
    runaway_limit: Option<u64>,
    /// The warnings of the runs, in order.
    warnings: Vec<Warning>,
}

impl<P: Predicates> Driver<'_, '_, P> {
    /// Refines until it finishes or has made `limit` Steiner points in all (or fewer under `S`
    /// or the runaway limit), and says how it ended.
    fn run_within(&mut self, limit: Option<u64>) -> Outcome {
        let lower = |a: Option<u64>, b: Option<u64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let (user_limit, runaway_limit) = (self.quality.max_steiner, self.runaway_limit);
        let steiner_limit = lower(lower(limit, user_limit), runaway_limit);
        match self.refinement.run(steiner_limit) {
            RunEnd::Cancelled => {
                self.warnings.push(Warning::Cancelled);
                Outcome::Cancelled
            }
            RunEnd::Finished => Outcome::Finished,
            RunEnd::AtLimit if user_limit.is_some() && steiner_limit == user_limit => {
                Outcome::UserBudget
            }
            RunEnd::AtLimit if runaway_limit.is_some() && steiner_limit == runaway_limit => {
                Outcome::Runaway
            }
            RunEnd::AtLimit => Outcome::RunBudget,
        }
    }

    /// Refinement toward an angle above 28.6°, where it may never end: it can cascade into ever
    /// smaller triangles near small input angles, and, above 30°, anywhere (every split of a
    /// skinny triangle makes an edge shorter than its shortest; see [`super::queue`]). Usually
    /// it ends, and refining straight toward the angle, as Triangle does, gives the best mesh;
    /// so that runs first, with a budget of new vertices for the input's size. A run that
    /// finishes within it stands. Otherwise the mesh refined to 28.6° (which always ends)
    /// tells how big a mesh the input needs: the straight run goes on within a multiple of
    /// that. Beyond it the straight run cascaded (measured on Triangle's
    /// `greenland` mesh with `rq34`: 5.4× Triangle's triangles, all in the interior, shortest
    /// edge first feeding on its own splits), and the unrefined mesh is refined again straight
    /// toward the angle in worst-angle order, within the same limit. Failing that, the 28.6°
    /// mesh is refined toward the angle with a small budget and whatever that leaves is
    /// repaired at 28.6°: the result meets the guaranteed angle, and a warning says that it does
    /// not meet the asked one.
    ///
    /// Coming back to an earlier state: two copies are made of the unrefined state (the input's
    /// size, small beside the refined meshes); the refined states in play are exchanged by
    /// moves ([`Refinement::exchange`]), never copied, so at most two refined meshes live at
    /// once. Replaying a deterministic run instead of keeping its result would double its time;
    /// an undo journal would have to log every operation of the mesh, the Delaunay inserter
    /// and constrain. An exchange empties the queues; the runs come in a fixed order, so the
    /// meshes (and the polls of `cancel` and `progress`) are deterministic.
    fn refine_beyond_the_guarantee(&mut self, angle: f64) -> Outcome {
        let mut aside = self.refinement.copy_aside(); // the unrefined state
        let unrefined_triangles = self.inside_triangle_count();
        self.refinement.set_angle(angle);
        // The budgets of the unrefined mesh; lattice points (which replace points the area
        // bounds would have asked for) do not count against them.
        let expected = self.size_estimate() + 1024;
        let plain = PLAIN_STRAIGHT_PER_TRIANGLE * unrefined_triangles + expected;
        self.seed();
        // The straight run stops at the plain budget: beyond it, it may go on only within the
        // limit that the 28.6° mesh sets (which it would have to meet anyway: measured on
        // Triangle's `greenland.ele` with `rq34`, an uninterrupted straight run made 922 000
        // new vertices in 0.7 s, 3.6× the limit, to be thrown away).
        match self.run_within(Some(self.steiner_points() + plain)) {
            Outcome::Finished => return Outcome::Finished,
            Outcome::RunBudget => {}
            outcome => return outcome,
        }
        // Live: the unrefined state, refined to 28.6°; aside: the straight run's, paused;
        // `unrefined`: the unrefined state again, for a run in the other order.
        self.refinement.exchange(&mut aside);
        let mut unrefined = self.refinement.copy_aside();
        self.refinement.set_angle(GUARANTEED_ANGLE);
        self.seed();
        let outcome = self.run_within(None);
        if outcome != Outcome::Finished {
            return outcome; // cancelled, or stopped by `S` or as a runaway
        }
        let guaranteed_triangles = self.inside_triangle_count();
        let limit = self.steiner_points() + GUARANTEED_MULTIPLE * guaranteed_triangles;
        if aside.steiner_points() <= limit {
            // Live: the straight run's state, going on; aside: the 28.6° mesh.
            self.refinement.exchange(&mut aside);
            self.refinement.set_angle(angle);
            let outcome = self.run_within(Some(limit));
            if outcome != Outcome::RunBudget {
                return outcome;
            }
            self.refinement.exchange(&mut aside);
        }
        // The straight run's state is no longer needed. Live: the unrefined state, straight
        // toward the angle, worst angle first; `unrefined`: the 28.6° mesh.
        drop(aside);
        self.refinement.exchange(&mut unrefined);
        self.refinement.set_order(QueueOrder::WorstAngle);
        self.refinement.set_angle(angle);
        self.seed();
        let outcome = self.run_within(Some(limit));
        if outcome != Outcome::RunBudget {
            return outcome;
        }
        self.refinement.exchange(&mut unrefined);
        self.refinement.set_order(QueueOrder::ShortestEdge);
        drop(unrefined);
        // Live: the 28.6° mesh, refined toward the angle with a small budget.
        self.refinement.set_angle(angle);
        let budget =
            self.steiner_points() + UNGUARANTEED_BUDGET_PER_TRIANGLE * guaranteed_triangles + 16;
        let outcome = self.run_within(Some(budget));
        if outcome != Outcome::RunBudget {
            return outcome;
        }
        self.refinement.set_angle(GUARANTEED_ANGLE);
        let outcome = self.run_within(None);
        self.warnings.push(Warning::AngleNotReached {
            angle,
            steiner_points: self.steiner_points(),
        });
        outcome
    }

    /// With `R` (not by default: measured on the refinement benchmark, it takes 2–4× the time of
    /// the refinement for 0.65–0.86× its triangles, where the time is what Triangle's users
    /// wait for; issue 36's frontier in README.md), decimates and polishes the finished mesh
    /// ([`Refinement::improve`]) and refines again
    /// what that left bad (rarely anything: a tie among cocircular vertices when a vertex is
    /// put back, an area bound after flips, a subsegment that a moved vertex encroaches). Up to
    /// [`GUARDED_IMPROVEMENT`] triangles, the mesh before stands if the one after has more
    /// triangles or an angle below θ or below the smallest the mesh had (with `Y`, new points
    /// may go where refinement had left bad triangles whole). Finished, or cancelled.
    fn improve(&mut self) -> Outcome {
        // Only when asked. Not under `S` (which counts insertions), nor with the user's test (which would be
        // asked about every triangle tried: slow where it is a script's callback, and it may
        // answer by a state of its own, as Triangle's callers' tests may).
        if !self.quality.reduce
            || self.quality.max_steiner.is_some()
            || self.quality.user_test.is_some()
            || !self.refinement.worth_improving()
        {
            return Outcome::Finished;
        }
        let triangles = self.inside_triangle_count();
        let mut before = (triangles <= GUARDED_IMPROVEMENT).then(|| self.refinement.copy_aside());
        // The angle the improved mesh must keep: θ, or the smaller angle the mesh had (an input
        // angle, or with `Y` a triangle only a segment's vertex could mend). Not the mesh's
        // exact smallest angle above θ: refinement again after the moves may make a triangle a
        // hair below it (Triangle's plate with four round holes, `pq`, 10^5 triangles: 20.0032°
        // against 20.0055°), and that threw away 31 % fewer triangles.
        let keep = smallest_angle_sin2(self.refinement.mesh()).min(self.refinement.angle_sin2());
        self.refinement.improve();
        self.refinement.forget_kept_whole();
        let outcome = self.run_within(None);
        if let Some(before) = before.as_mut() {
            let worse = outcome != Outcome::Finished
                || self.inside_triangle_count() > triangles
                || smallest_angle_sin2(self.refinement.mesh()) < keep;
            if worse && outcome != Outcome::Cancelled {
                self.refinement.exchange(before);
                return Outcome::Finished;
            }
        }
        outcome
    }

    /// Seeds the unrefined domain with lattice points where a fixed area bound governs
    /// ([`super::lattice`]): not with the user's test or an `S` budget (there is no runaway limit
    /// then), nor with `Y`/`YY` (segments kept whole: the band between a lattice and a segment
    /// that cannot be split may keep smaller angles than refinement alone leaves), and within the runaway limit (an area bound asking for billions of triangles is
    /// stopped as a runaway). Before the copy of the unrefined state above 28.6° (which then
    /// stays small), and again on that state when it is refined at 28.6°.
    fn seed(&mut self) {
        let segments_split = self.quality.no_steiner_on_segments == 0;
        if let (true, true, Some(limit)) = (
            self.quality.area_lattice,
            segments_split,
            self.runaway_limit,
        ) {
            super::lattice::seed_lattices(
                &mut self.refinement,
                self.domain,
                self.quality.max_area,
                self.quality.variable_area,
                limit,
                self.quality.min_angle,
            );
        }
    }

    fn steiner_points(&self) -> u64 {
        self.refinement.tally().steiner_points
    }

    fn inside_triangle_count(&self) -> u64 {
        inside_triangle_count(self.refinement.mesh())
    }

    fn size_estimate(&self) -> u64 {
        size_estimate::<P>(self.refinement.mesh(), self.domain, self.quality)
    }
}

/// The sine squared of the smallest angle of the domain's triangles (1 for none).
fn smallest_angle_sin2(mesh: &Mesh) -> f64 {
    worst_triangle(mesh).map_or(1.0, |(_, sin2)| sin2)
}

/// The resolutions refinement works at, from the vertices: the squared snapping distance (a
/// vertex this close to an interior subsegment becomes a vertex of it: 2⁻⁴⁰ of the extent,
/// where rounding makes one line of a segment and a vertex beside it), the squared floor below
/// which no edge is made, and the squared extent.
///
/// The floor is 2⁻⁵⁰ of the largest coordinate magnitude: four to eight units in the last place
/// there, the finest spacing at which a rounded split point still lands where it was meant to
/// (between the vertices it was computed from). Triangle refines as fine as the doubles allow,
/// so a floor relative to the extent (2⁻⁴⁰ of it, some four thousand units in the last place)
/// left the triangles around a vertex pair 10⁻¹¹ of the domain apart unsplit where Triangle
/// meets θ.
fn resolution(mesh: &Mesh) -> Resolution {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in mesh.points() {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let magnitude = lo[0]
        .abs()
        .max(hi[0].abs())
        .max(lo[1].abs())
        .max(hi[1].abs());
    let extent = (hi[0] - lo[0])
        .abs()
        .max((hi[1] - lo[1]).abs())
        .max(magnitude * 1e-3)
        .max(f64::MIN_POSITIVE);
    let snap = extent * 2f64.powi(-40);
    let floor = (magnitude * 2f64.powi(-52)).max(f64::MIN_POSITIVE);
    Resolution {
        snap2: snap * snap,
        floor2: floor * floor,
        extent2: extent * extent,
    }
}

/// What [`resolution`] gives (each squared).
struct Resolution {
    snap2: f64,
    floor2: f64,
    extent2: f64,
}

/// Twice the area of the domain's triangles.
fn doubled_domain_area<P: Predicates>(mesh: &Mesh) -> f64 {
    mesh.triangles()
        .filter(|&t| inside(mesh, t))
        .map(|t| {
            let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
            P::orient2d(a, b, c)
        })
        .sum()
}

fn inside_triangle_count(mesh: &Mesh) -> u64 {
    mesh.triangles().filter(|&t| inside(mesh, t)).count() as u64
}

/// About how many vertices the area bounds (global, regional, per triangle) ask for: four times
/// the number of triangles of the largest allowed areas that cover the domain.
fn size_estimate<P: Predicates>(mesh: &Mesh, domain: &Domain, quality: &Quality<'_>) -> u64 {
    let triangles: f64 = mesh
        .triangles()
        .filter(|&t| inside(mesh, t))
        .map(|t| {
            let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
            let area = 0.5 * P::orient2d(a, b, c);
            area_bound(quality.max_area, quality.variable_area, domain, mesh.tag(t))
                .map_or(0.0, |bound| area / bound)
        })
        .sum();
    (4.0 * triangles).min(1e12) as u64
}
