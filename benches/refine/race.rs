//! Timing of one case for the table and the size sweep: our `triangulate` and Triangle's through
//! their C ABIs on the same input, in this process, interleaved (ours, Triangle, ours, …).
//!
//! The first call of each gives its time; a case is *short* when Triangle's first call (ours,
//! without Triangle) takes less than [`SHORT`]. A short case repeats each side until it has spent
//! about the budget (at least `reps` calls, at most [`MOST_CALLS`]) and takes each side's best
//! call, as sub-millisecond calls are best measured on this shared machine; any other case makes
//! `reps` calls of each (the first included; fewer where they would take longer than a given
//! time, one at least) and takes the medians (the lower one of an even count: interference only
//! slows a call down). The calls of the two sides are spread evenly over the same span of time.

use std::time::Duration;

use crate::common;
use common::call::{MeshInput, Triangulation};
use common::reference::Reference;
use common::timing::{timed_call, Library, Times};

/// Below this first-call time of Triangle's a case is short (best of many calls).
pub const SHORT: Duration = Duration::from_millis(1);
/// The most calls of one side in a short case.
pub const MOST_CALLS: usize = 2000;

/// One side's result: its wall-clock and process CPU time (each the best or the median of its
/// own samples), its number of calls, its last mesh.
pub struct Side {
    pub time: Duration,
    pub cpu: Duration,
    pub calls: usize,
    pub mesh: Triangulation,
}

/// Both sides' results; `best`: the times are the best calls (a short case), else medians.
pub struct Race {
    pub ours: Option<Side>,
    pub theirs: Option<Side>,
    pub best: bool,
}

impl Race {
    /// `best of 3/400` or `median of 3/3`: the statistic and the calls (ours/Triangle's).
    pub fn calls(&self) -> String {
        let n = |s: &Option<Side>| s.as_ref().map_or("—".to_string(), |s| s.calls.to_string());
        format!(
            "{} {}/{}",
            if self.best { "best of" } else { "median of" },
            n(&self.ours),
            n(&self.theirs)
        )
    }
}

/// Times `switches` on `input`: ours when `ours`, Triangle's when `theirs` is given (only pass
/// input Triangle accepts): `reps` calls each, short cases (see the module doc) until each side
/// has spent about `budget`, others only as many as fit in `most_time` (one at least). Panics if
/// a call fails.
pub fn race(
    switches: &str,
    input: &MeshInput,
    ours: bool,
    theirs: Option<&'static Reference>,
    reps: usize,
    budget: Duration,
    most_time: Duration,
) -> Race {
    let libraries: Vec<Library> = [ours.then_some(Library::Ours), theirs.map(Library::Triangle)]
        .into_iter()
        .flatten()
        .collect();
    let mut samples: Vec<Vec<Duration>> = vec![Vec::new(); libraries.len()];
    let mut cpu: Vec<Vec<Duration>> = vec![Vec::new(); libraries.len()];
    let mut meshes: Vec<Option<Triangulation>> = vec![None; libraries.len()];
    let mut call = |k: usize, samples: &mut Vec<Vec<Duration>>| {
        let (times, mesh): (Times, Triangulation) = timed_call(libraries[k], switches, input);
        samples[k].push(times.wall);
        cpu[k].push(times.cpu);
        meshes[k] = Some(mesh);
    };
    for k in 0..libraries.len() {
        call(k, &mut samples);
    }
    // Triangle's first call decides (the last library), ours alone otherwise.
    let best = samples.last().is_some_and(|s| s[0] < SHORT);
    let reps = reps.max(1);
    let wanted: Vec<usize> = samples
        .iter()
        .map(|s| {
            if best {
                let per_call = s[0].as_secs_f64().max(1e-7);
                ((budget.as_secs_f64() / per_call).ceil() as usize).clamp(reps, MOST_CALLS)
            } else {
                let fit = (most_time.as_secs_f64() / s[0].as_secs_f64()).floor() as usize;
                fit.clamp(1, reps)
            }
        })
        .collect();
    // Spread the calls evenly: next is the side that has made the smallest part of its calls.
    loop {
        let next = (0..libraries.len())
            .filter(|&k| samples[k].len() < wanted[k])
            .min_by(|&a, &b| {
                let part = |k: usize| samples[k].len() as f64 / wanted[k] as f64;
                part(a).total_cmp(&part(b))
            });
        match next {
            Some(k) => call(k, &mut samples),
            None => break,
        }
    }
    let statistic = |s: Vec<Duration>| {
        if best {
            *s.iter().min().expect("one call")
        } else {
            lower_median(s)
        }
    };
    let mut sides = samples
        .into_iter()
        .zip(cpu)
        .zip(meshes)
        .map(|((s, c), mesh)| Side {
            calls: s.len(),
            time: statistic(s),
            cpu: statistic(c),
            mesh: mesh.expect("one call"),
        });
    let ours = if ours { sides.next() } else { None };
    let theirs = sides.next();
    Race { ours, theirs, best }
}

/// The median of `samples` (not empty), the lower one of an even count.
fn lower_median(mut samples: Vec<Duration>) -> Duration {
    samples.sort();
    samples[(samples.len() - 1) / 2]
}

/// A duration in milliseconds with three significant digits or so.
pub fn ms(d: Duration) -> String {
    let ms = d.as_secs_f64() * 1e3;
    if ms < 1.0 {
        format!("{ms:.3}")
    } else if ms < 10.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.1}")
    }
}

/// The geometric mean of `values` (1 for none).
pub fn geometric_mean(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 1.0;
    }
    (values.iter().map(|v| v.ln()).sum::<f64>() / values.len() as f64).exp()
}
