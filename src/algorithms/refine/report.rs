//! What a refinement reports: the Steiner points it made and typed warnings, whose text (their
//! `Display`) is what the library, the C ABI and the command line print.

use std::fmt;

use super::GUARANTEED_ANGLE;

/// The outcome of a refinement.
#[derive(Debug, Default)]
pub struct Report {
    /// New vertices made by refinement.
    pub steiner_points: u64,
    /// New vertices made in all runs, kept or not (the unit of the progress reports).
    pub work: u64,
    /// What the caller should know about the mesh, in the order it happened.
    pub warnings: Vec<Warning>,
    /// The refined mesh could not be moved onto the caller's grid ([`super::Quality::caller_grid`])
    /// without changing its shape (it is left in the engine's frame): the caller should refine
    /// in its own frame instead.
    pub off_grid: bool,
}

/// Why a refined mesh may fall short of what was asked. Every mesh is valid all the same.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Warning {
    /// The caller cancelled refinement.
    Cancelled,
    /// The asked minimum angle (above [`GUARANTEED_ANGLE`]) needed more Steiner points than the
    /// budgets beyond the guarantee allow: the mesh meets the guaranteed angle only.
    AngleNotReached {
        /// The asked minimum angle, in degrees.
        angle: f64,
        /// The Steiner points made in all.
        steiner_points: u64,
    },
    /// Refinement made far more vertices than the input and its area bounds account for and was
    /// stopped.
    Runaway {
        /// The Steiner points made in all.
        steiner_points: u64,
    },
    /// Triangles or segments left unsplit where the precision of floating-point numbers is
    /// exhausted.
    PrecisionExhausted {
        /// How many.
        unsplit: u64,
    },
    /// The `S` budget stopped refinement with bad triangles (or, with `D`, encroached
    /// subsegments) left.
    BudgetSpent {
        /// The budget: at most this many Steiner points.
        limit: u64,
        /// How many are left.
        unmet: u64,
    },
    /// Bad triangles left unsplit because that needs vertices on segments that `Y` keeps whole.
    SegmentsKeptWhole {
        /// How many.
        unsplit: u64,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Warning::Cancelled => {
                write!(f, "Refinement was cancelled; the mesh is valid but not refined.")
            }
            Warning::AngleNotReached {
                angle,
                steiner_points,
            } => write!(
                f,
                "A minimum angle of {angle}° is above {GUARANTEED_ANGLE}°, the largest for which Delaunay \
                 refinement is guaranteed to terminate, and this input needs more: refinement stopped after \
                 {steiner_points} Steiner points with some angles below {angle}° but none below {GUARANTEED_ANGLE}° (the mesh \
                 is valid)."
            ),
            Warning::Runaway { steiner_points } => write!(
                f,
                "Refinement stopped after {steiner_points} Steiner points, far more than this input and its area bounds \
                 account for: some of its features are too thin for the minimum angle (the mesh is valid; \
                 the S switch sets a limit of your own)."
            ),
            Warning::BudgetSpent { limit, unmet } => write!(
                f,
                "The S budget of {limit} Steiner points was spent with {unmet} triangles or segments below the \
                 bounds left; the mesh is valid but may have angles below the minimum or triangles above \
                 the maximum area."
            ),
            Warning::PrecisionExhausted { unsplit } => write!(
                f,
                "Refinement left {unsplit} triangles or segments unsplit: the precision of floating-point numbers is \
                 exhausted near some vertices. The mesh is valid but may have angles below the minimum there."
            ),
            Warning::SegmentsKeptWhole { unsplit } => write!(
                f,
                "Refinement left {unsplit} bad triangles unsplit: that needs new vertices on segments, which the Y switch \
                 forbids. The mesh is valid but may have angles below the minimum or triangles above the maximum area."
            ),
        }
    }
}
