//! Insertion orders for incremental Delaunay triangulation.
//!
//! Inserting points along a Hilbert curve keeps consecutive points close, so the walk that
//! locates each point is short and its memory accesses hit the cache (PERFORMANCE-NOTES.md).
//! Both orders here insert the points in random rounds of growing size, each round in Hilbert
//! order: the biased randomized insertion order (BRIO) of Amenta, Choi and Rote, "Incremental
//! constructions con BRIO" (2003). With rounds that double (`i`), it keeps the expected
//! O(n log n) bound of randomized insertion. The default grows the rounds eightfold (a
//! multiscale order, as in CGAL's spatial sorting): a coarse sketch of the whole point set comes
//! first, so the triangulation never grows as one long Hilbert snake with a ragged hull that
//! each new point must flip its way into; at 10^6 uniform points this takes a third off the time
//! of inserting in plain Hilbert order.
//!
//! The curve's grid adapts to the points: a round's points that share one of the 4096² cells of
//! the whole box are ordered again along a curve over their own box, and so on down
//! ([`order_crowded_cells`]). With a grid of fixed resolution, Kuzmin's distribution (most of
//! 10^6 points within a few units of the origin, a few 10^6 away) put nearly every point in one
//! cell, in input order: each walk crossed the cell, some 14 000 instructions per point at 10^5
//! points and 110 s for 10^6 (against 1 700 instructions and 0.35 s on uniform points).

use super::hilbert::{hilbert_key_of, hilbert_sorted_keys, HILBERT_BITS, KEY_SHIFT};
use crate::geometry::Point;
use std::mem::MaybeUninit;

/// All point indices in Hilbert-curve order (among points with equal keys the earlier input
/// point first).
pub fn hilbert_order(points: &[Point]) -> Vec<u32> {
    hilbert_sorted_keys(points)
        .into_iter()
        .map(|k| k as u32)
        .collect()
}

/// Seed of the default order's rounds.
const MULTISCALE_SEED: u64 = 0x6D75_6C74_6973_6361;

/// The default insertion order: rounds growing eightfold, each in Hilbert order.
pub fn multiscale_order(points: &[Point]) -> Vec<u32> {
    rounds_in_hilbert_order(points, MULTISCALE_SEED, 3)
}

/// The order of `i`: a biased randomized insertion order, rounds doubling in size.
pub fn brio_order(points: &[Point], seed: u64) -> Vec<u32> {
    rounds_in_hilbert_order(points, seed, 1)
}

/// [`multiscale_order`] and the points in that order; the sort works in `room` when it is given
/// with room for two words per point (see [`OrderKind::order_and_points`]).
pub fn multiscale_order_and_points(
    points: &[Point],
    room: Option<&mut [MaybeUninit<u64>]>,
) -> (Vec<u32>, Vec<Point>) {
    rounds_in_hilbert_order_and_points(points, |_| true, MULTISCALE_SEED, 3, room)
}

/// [`multiscale_order_and_points`] of the points that `keep` accepts (numbered as in `points`;
/// each with the round and Hilbert key it has among all of them): one side of a split taken
/// straight from all the points, without copying it out first. `room` as there, for all the
/// points.
pub fn multiscale_order_and_points_where(
    points: &[Point],
    keep: impl Fn(Point) -> bool,
    room: Option<&mut [MaybeUninit<u64>]>,
) -> (Vec<u32>, Vec<Point>) {
    rounds_in_hilbert_order_and_points(points, keep, MULTISCALE_SEED, 3, room)
}

/// [`brio_order`] and the points in that order (`room` as for [`multiscale_order_and_points`]).
pub fn brio_order_and_points(
    points: &[Point],
    seed: u64,
    room: Option<&mut [MaybeUninit<u64>]>,
) -> (Vec<u32>, Vec<Point>) {
    rounds_in_hilbert_order_and_points(points, |_| true, seed, 1, room)
}

/// Which insertion order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderKind {
    /// [`multiscale_order`], the default.
    Multiscale,
    /// [`brio_order`] with this seed (`i`).
    Brio(u64),
}

impl OrderKind {
    /// The order and the points in it (`room` as for [`multiscale_order_and_points`]).
    pub fn order_and_points(
        self,
        points: &[Point],
        room: Option<&mut [MaybeUninit<u64>]>,
    ) -> (Vec<u32>, Vec<Point>) {
        match self {
            OrderKind::Multiscale => multiscale_order_and_points(points, room),
            OrderKind::Brio(seed) => brio_order_and_points(points, seed, room),
        }
    }
}

/// Rounds of the orders: more than enough for any point count (the first rounds stay empty).
const ROUNDS: usize = 32;

/// The round of the next point: round r from the last takes each point with probability
/// (1 − q)·q^r, q = 2^−`growth_bits`: the number of trailing zero bits of a uniform random word,
/// in steps of `growth_bits` (`rounds`, from [`rounds_by_trailing_zeros`]).
fn next_round(state: &mut u64, rounds: &[u8; 65]) -> u32 {
    u32::from(rounds[splitmix64(state).trailing_zeros() as usize])
}

/// [`next_round`]'s round for each count of trailing zero bits (0 to 64): one lookup per point
/// instead of a division.
fn rounds_by_trailing_zeros(growth_bits: u32) -> [u8; 65] {
    std::array::from_fn(|zeros| {
        let from_last = (zeros as u32 / growth_bits).min(ROUNDS as u32 - 1);
        (ROUNDS as u32 - 1 - from_last) as u8
    })
}

/// All point indices in random rounds, each in Hilbert order; the last round holds a fraction
/// 1 − 2^−`growth_bits` of the points, the one before it that fraction of the rest, and so on.
/// Deterministic for a given `seed`: point i's round comes from the i-th number of the seeded
/// generator. Within a round, points with equal keys come in input order.
///
/// Linear time, in one word per point that holds its round (5 bits), its Hilbert key (32) and
/// its index (27): sorting the words sorts by round, then key, then index; then the crowded
/// cells are ordered again ([`order_crowded_cells`]). One counting pass
/// scatters them by round and the key's top 8 bits (buckets of a few thousand words at 10^6
/// points); each bucket is then sorted where it lies in the cache, by radix passes over the
/// key's other 16 bits (the buckets keep the input order of the words, and the passes are
/// stable). Against three radix passes over all the words and a pass by round, this moves the
/// words through memory once.
fn rounds_in_hilbert_order(points: &[Point], seed: u64, growth_bits: u32) -> Vec<u32> {
    if points.len() >= 1 << INDEX_BITS {
        return rounds_in_hilbert_order_by_passes(points, seed, growth_bits);
    }
    let mut room = Vec::with_capacity(2 * points.len());
    let (sorted, _) = sorted_words::<false>(
        points,
        |_| true,
        seed,
        growth_bits,
        room.spare_capacity_mut(),
    );
    let index_mask = (1u64 << INDEX_BITS) - 1;
    sorted.iter().map(|&w| (w & index_mask) as u32).collect()
}

/// [`rounds_in_hilbert_order`] and the points in that order. The points travel with their
/// words through the scatter by bucket (read in input order, written where their bucket
/// lies) and the sorts of the buckets (in the cache), instead of being gathered afterwards in
/// the order's random sequence of input positions, whose reads miss the cache and the TLB.
///
/// The sort works in `room` when it is given with room for two words per point (its contents
/// are overwritten), else in an allocation of its own.
fn rounds_in_hilbert_order_and_points(
    points: &[Point],
    keep: impl Fn(Point) -> bool,
    seed: u64,
    growth_bits: u32,
    room: Option<&mut [MaybeUninit<u64>]>,
) -> (Vec<u32>, Vec<Point>) {
    let n = points.len();
    if n >= 1 << INDEX_BITS {
        // Indices too large for the words: the kept points are gathered and ordered by passes.
        let kept: Vec<u32> = (0..n as u32)
            .filter(|&i| keep(points[i as usize]))
            .collect();
        let kept_points: Vec<Point> = kept.iter().map(|&i| points[i as usize]).collect();
        let order: Vec<u32> = rounds_in_hilbert_order_by_passes(&kept_points, seed, growth_bits)
            .into_iter()
            .map(|v| kept[v as usize])
            .collect();
        let sorted = order.iter().map(|&v| points[v as usize]).collect();
        return (order, sorted);
    }
    let mut own: Vec<u64>;
    let room = match room {
        Some(room) if room.len() >= 2 * n => room,
        _ => {
            own = Vec::with_capacity(2 * n);
            own.spare_capacity_mut()
        }
    };
    let (sorted, sorted_points) = sorted_words::<true>(points, keep, seed, growth_bits, room);
    let index_mask = (1u64 << INDEX_BITS) - 1;
    let order = sorted.iter().map(|&w| (w & index_mask) as u32).collect();
    (order, sorted_points)
}

/// Bits of a point's index in the words of [`sorted_words`].
const INDEX_BITS: u32 = 27;

/// Up to this many points, [`sorted_words`] sorts by comparison: below it the histogram over
/// every (round, top key bits) bucket costs more than the sort.
const SMALL_SORT: usize = 1024;

/// Sorts the words of [`rounds_in_hilbert_order`] for the points that `keep` accepts (`m` of
/// the `n`) into `room[m..2m]` (`room[..m]` is the sort's spare room), which it returns, and
/// (with `POINTS`) the kept points in the same order (else an empty list). A kept point's round
/// and Hilbert key are those it has among all the points. Only the `2m` words used are written:
/// the room's pages beyond them are not touched (a fresh page costs microseconds here, and the
/// room of one side of a split is sized for all the points).
/// Fewer than 2^[`INDEX_BITS`] points; `room` holds at least two words per point.
fn sorted_words<'r, const POINTS: bool>(
    points: &[Point],
    keep: impl Fn(Point) -> bool,
    seed: u64,
    growth_bits: u32,
    room: &'r mut [MaybeUninit<u64>],
) -> (&'r [u64], Vec<Point>) {
    const TOP_BITS: u32 = 8;
    let key = hilbert_key_of(points);
    let rounds = rounds_by_trailing_zeros(growth_bits);
    let mut m = 0;
    for (i, &p) in points.iter().enumerate() {
        // Only the kept points' words: a branch that is mispredicted about half the time on
        // one side of a split costs less than a key and a round for each point of the other.
        if keep(p) {
            let round = u64::from(round_at(seed, i, &rounds));
            room[m]
                .write((round << (32 + INDEX_BITS)) | (u64::from(key(p)) << INDEX_BITS) | i as u64);
            m += 1;
        }
    }
    // From here on, `n` counts the kept points.
    let n = m;
    let (words, sorted) = room[..2 * n].split_at_mut(n);
    // SAFETY: the loop above wrote the first `m` words, and `MaybeUninit<u64>` has the layout
    // of `u64`.
    let words = unsafe { &mut *(words as *mut [MaybeUninit<u64>] as *mut [u64]) };
    if n <= SMALL_SORT {
        // A few points: one comparison sort. The words are distinct (their indices differ),
        // so it gives the order of the buckets and passes below, whose histogram of
        // `ROUNDS << TOP_BITS` buckets alone costs more than sorting these.
        words.sort_unstable();
        let mut sorted_points: Vec<Point> = Vec::with_capacity(if POINTS { n } else { 0 });
        let index_mask = (1u64 << INDEX_BITS) - 1;
        for (slot, &w) in sorted.iter_mut().zip(words.iter()) {
            slot.write(w);
            if POINTS {
                sorted_points.push(points[(w & index_mask) as usize]);
            }
        }
        // SAFETY: the loop wrote each of the `n` words of `sorted`.
        let sorted = unsafe { &mut *(sorted as *mut [MaybeUninit<u64>] as *mut [u64]) };
        order_crowded_cells(
            sorted,
            &mut sorted_points,
            points,
            words,
            &mut Vec::new(),
            INDEX_BITS,
            INDEX_BITS + KEY_SHIFT,
        );
        return (sorted, sorted_points);
    }
    // The bucket of a word: its round and the top bits of its key.
    let bucket = |w: u64| (w >> (32 + INDEX_BITS - TOP_BITS)) as usize;
    let mut starts = vec![0usize; (ROUNDS << TOP_BITS) + 1];
    for &w in words.iter() {
        starts[bucket(w) + 1] += 1;
    }
    for b in 1..starts.len() {
        starts[b] += starts[b - 1];
    }
    let mut sorted_points: Vec<Point> = if POINTS {
        crate::memory::with_capacity_on_huge_pages(n)
    } else {
        Vec::new()
    };
    let mut next = starts.clone();
    let index_mask = (1u64 << INDEX_BITS) - 1;
    let room_for_points = &mut sorted_points.spare_capacity_mut()[..if POINTS { n } else { 0 }];
    for &w in words.iter() {
        let b = bucket(w);
        sorted[next[b]].write(w);
        if POINTS {
            // The words are in input order: these reads go forward through the points.
            room_for_points[next[b]].write(points[(w & index_mask) as usize]);
        }
        next[b] += 1;
    }
    if POINTS {
        // SAFETY: the scatter wrote each of the first `n` slots once (the bucket starts
        // partition 0..n, and each bucket's slots are filled by its words), within capacity `n`.
        unsafe { sorted_points.set_len(n) };
    }
    // SAFETY: as for the points, the scatter wrote each of the `n` words of `sorted`.
    let sorted = unsafe { &mut *(sorted as *mut [MaybeUninit<u64>] as *mut [u64]) };
    drop(next);
    let spare = words;
    let largest = starts.windows(2).map(|r| r[1] - r[0]).max().unwrap_or(0);
    let mut spare_points: Vec<Point> = if POINTS {
        vec![[0.0; 2]; largest]
    } else {
        Vec::new()
    };
    for range in starts.windows(2) {
        let (from, to) = (range[0], range[1]);
        let bucket_points: &mut [Point] = if POINTS {
            &mut sorted_points[from..to]
        } else {
            &mut []
        };
        sort_bucket(
            &mut sorted[from..to],
            bucket_points,
            spare,
            &mut spare_points,
            INDEX_BITS,
        );
    }
    order_crowded_cells(
        sorted,
        &mut sorted_points,
        points,
        spare,
        &mut spare_points,
        INDEX_BITS,
        INDEX_BITS + KEY_SHIFT,
    );
    (sorted, sorted_points)
}

/// Sorts the words of one bucket (their top bits equal, their indices increasing) by the key
/// bits below its top 8 (the key's, above bit `index_bits`): stable 8-bit counting passes
/// through `spare`, two for the 16 bits left of a 24-bit key ([`HILBERT_BITS`]) (small
/// buckets by insertion: the words are distinct, so any sort gives the same order). The
/// bucket's `points` (one per word, or none at all) move with their words.
fn sort_bucket(
    words: &mut [u64],
    points: &mut [Point],
    spare: &mut [u64],
    spare_points: &mut [Point],
    index_bits: u32,
) {
    sort_by_key_bits(
        words,
        points,
        spare,
        spare_points,
        index_bits + KEY_SHIFT,
        (2 * HILBERT_BITS - 8).div_ceil(8),
    );
}

/// Sorts `words` (their indices increasing among equal keys) by `passes` bytes of key from bit
/// `low` up: stable 8-bit counting passes through `spare` (small slices by insertion: the words
/// are distinct, so any sort gives the same order). The `points` (one per word, or none at
/// all) move with their words.
fn sort_by_key_bits(
    words: &mut [u64],
    points: &mut [Point],
    spare: &mut [u64],
    spare_points: &mut [Point],
    low: u32,
    passes: u32,
) {
    let with_points = !points.is_empty();
    if words.len() <= 64 {
        for i in 1..words.len() {
            let (w, p) = (words[i], if with_points { points[i] } else { [0.0; 2] });
            let mut j = i;
            while j > 0 && words[j - 1] > w {
                words[j] = words[j - 1];
                if with_points {
                    points[j] = points[j - 1];
                }
                j -= 1;
            }
            words[j] = w;
            if with_points {
                points[j] = p;
            }
        }
        return;
    }
    let n = words.len();
    let spare = &mut spare[..n];
    let spare_points: &mut [Point] = if with_points {
        &mut spare_points[..n]
    } else {
        &mut []
    };
    // The passes go back and forth between the bucket and the spare room; one copy at the end
    // if the words end up in the spare room.
    let mut in_spare = false;
    for pass in 0..passes {
        let shift = low + 8 * pass;
        let digit = |w: u64| ((w >> shift) & 0xff) as usize;
        let (from, to, from_points, to_points) = if in_spare {
            (&*spare, &mut *words, &*spare_points, &mut *points)
        } else {
            (&*words, &mut *spare, &*points, &mut *spare_points)
        };
        let mut counts = [0usize; 257];
        for &w in from {
            counts[digit(w) + 1] += 1;
        }
        if counts.contains(&n) {
            continue; // one digit value for all words: the pass would not move anything
        }
        for d in 1..257 {
            counts[d] += counts[d - 1];
        }
        if with_points {
            for (&w, &p) in from.iter().zip(from_points) {
                let d = digit(w);
                to[counts[d]] = w;
                to_points[counts[d]] = p;
                counts[d] += 1;
            }
        } else {
            for &w in from {
                let d = digit(w);
                to[counts[d]] = w;
                counts[d] += 1;
            }
        }
        in_spare = !in_spare;
    }
    if in_spare {
        words.copy_from_slice(spare);
        points.copy_from_slice(spare_points);
    }
}

/// Runs of more than this many words with one round and one key (points that share a cell of
/// the curve's grid) are ordered again ([`order_crowded_cells`]): within a run the order is the
/// input's, as good as random, and a walk from one point to the next may cross all the
/// triangles of the cell.
const CROWDED: usize = 16;

/// Orders every run of more than [`CROWDED`] consecutive `words` with one round and one key
/// along a Hilbert curve over the run's own bounding box (the run's new keys replace the old
/// ones in its words), again within the runs of equal new keys that are still crowded, and so on
/// down: the order's resolution follows the points' density, however many orders of magnitude
/// it spans (Kuzmin's distribution, a dense patch in a wide square), instead of stopping at
/// the 4096² cells of the whole box. A run whose points all get one key (a single position:
/// duplicates) stays in input order. Each level costs a pass over the crowded runs alone;
/// where no cell is crowded (uniform points), one scan of the words.
///
/// A word holds the point's index in its bits below `index_bits`, its key's 24 bits from bit
/// `low` up, and its round above them. `points` are the words' points in the same order, which
/// move with them, or empty: the points are then read as `all[index]`. `spare` has room for
/// the longest run; `spare_points` grows to it when needed.
fn order_crowded_cells(
    words: &mut [u64],
    points: &mut [Point],
    all: &[Point],
    spare: &mut [u64],
    spare_points: &mut Vec<Point>,
    index_bits: u32,
    low: u32,
) {
    let with_points = !points.is_empty();
    let index_mask = (1u64 << index_bits) - 1;
    let key_mask = ((1u64 << (2 * HILBERT_BITS)) - 1) << low;
    let mut todo: Vec<std::ops::Range<usize>> = Vec::new();
    crowded_runs(words, low, 0, &mut todo);
    let mut gathered: Vec<Point> = Vec::new();
    while let Some(range) = todo.pop() {
        let run = &mut words[range.clone()];
        let run_points: &[Point] = if with_points {
            &points[range.clone()]
        } else {
            gathered.clear();
            gathered.extend(run.iter().map(|&w| all[(w & index_mask) as usize]));
            &gathered
        };
        let key = hilbert_key_of(run_points);
        for (w, &p) in run.iter_mut().zip(run_points) {
            *w = (*w & !key_mask) | (u64::from(key(p) >> KEY_SHIFT) << low);
        }
        if with_points && spare_points.len() < run.len() {
            spare_points.resize(run.len(), [0.0; 2]);
        }
        let (run_points, spare_points): (&mut [Point], &mut [Point]) = if with_points {
            (&mut points[range.clone()], spare_points)
        } else {
            (&mut [], &mut [])
        };
        sort_by_key_bits(
            run,
            run_points,
            spare,
            spare_points,
            low,
            (2 * HILBERT_BITS).div_ceil(8),
        );
        let before = todo.len();
        crowded_runs(&words[range.clone()], low, range.start, &mut todo);
        if todo.len() == before + 1 && todo[before] == range {
            // One key for the whole run: its box is a point (or too wide for the arithmetic).
            todo.pop();
        }
    }
}

/// Adds to `todo` the ranges (offset by `offset`) of the runs of more than [`CROWDED`]
/// consecutive `words` equal from bit `low` up (the words are sorted by those bits).
///
/// Words are compared [`CROWDED`]` / 2` apart: a run of more than [`CROWDED`] words holds two
/// probes that far apart, equal, and only there is the run's extent looked for. Where no cell
/// is crowded this reads one word in eight.
fn crowded_runs(words: &[u64], low: u32, offset: usize, todo: &mut Vec<std::ops::Range<usize>>) {
    const STRIDE: usize = CROWDED / 2;
    let cell = |i: usize| words[i] >> low;
    let mut probe = 0;
    while probe + STRIDE < words.len() {
        if cell(probe) != cell(probe + STRIDE) {
            probe += STRIDE;
            continue;
        }
        let c = cell(probe);
        let mut start = probe;
        while start > 0 && cell(start - 1) == c {
            start -= 1;
        }
        let mut end = probe + STRIDE + 1;
        while end < words.len() && cell(end) == c {
            end += 1;
        }
        if end - start > CROWDED {
            todo.push(offset + start..offset + end);
        }
        probe = end;
    }
}

/// [`rounds_in_hilbert_order`] for 2^27 points or more (whose indices do not fit in its words):
/// the Hilbert order by radix sort, then a stable counting sort by round.
fn rounds_in_hilbert_order_by_passes(points: &[Point], seed: u64, growth_bits: u32) -> Vec<u32> {
    let mut state = seed;
    let rounds = rounds_by_trailing_zeros(growth_bits);
    let round_of: Vec<u8> = (0..points.len())
        .map(|_| next_round(&mut state, &rounds) as u8)
        .collect();
    let mut starts = [0usize; ROUNDS + 1];
    for &r in &round_of {
        starts[r as usize + 1] += 1;
    }
    for r in 1..=ROUNDS {
        starts[r] += starts[r - 1];
    }
    // Words of round (5 bits), key (24) and index (32), in order of round, key and index.
    let mut words = vec![0u64; points.len()];
    for key in hilbert_sorted_keys(points) {
        let v = key as u32;
        let r = round_of[v as usize] as usize;
        words[starts[r]] = ((r as u64) << 56) | ((key >> (32 + KEY_SHIFT)) << 32) | u64::from(v);
        starts[r] += 1;
    }
    let mut spare = vec![0u64; points.len()];
    order_crowded_cells(
        &mut words,
        &mut [],
        points,
        &mut spare,
        &mut Vec::new(),
        32,
        32,
    );
    words.into_iter().map(|w| w as u32).collect()
}

/// [`next_round`] for the point at `index`: the generator's state after `index` steps from
/// `seed` is `seed + index·γ` (SplitMix64 steps by a constant), so a point's round needs none
/// of the points before it.
fn round_at(seed: u64, index: usize, rounds: &[u8; 65]) -> u32 {
    let mut state = seed.wrapping_add(SPLITMIX_GAMMA.wrapping_mul(index as u64));
    next_round(&mut state, rounds)
}

/// SplitMix64's step.
const SPLITMIX_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny, good-quality seeded generator.
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(SPLITMIX_GAMMA);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` points uniform in the unit square, from the generator's state `s`.
    fn uniform(n: usize, s: &mut u64) -> Vec<Point> {
        let mut unit = || splitmix64(s) as f64 / u64::MAX as f64;
        (0..n).map(|_| [unit(), unit()]).collect()
    }

    /// `n` points on a 37 × 23 grid: many ties of key and many duplicates.
    fn grid(n: usize) -> Vec<Point> {
        (0..n)
            .map(|i| [(i % 37) as f64, ((i * 7) % 23) as f64])
            .collect()
    }

    /// The one-word sort gives the order of the radix passes (which large inputs use), ties and
    /// degenerate boxes included.
    #[test]
    fn both_ways_of_sorting_rounds_agree() {
        let mut s = 11;
        let uniform = uniform(200_000, &mut s);
        let grid = grid(50_000);
        let mut unit = || splitmix64(&mut s) as f64 / u64::MAX as f64;
        let line: Vec<Point> = (0..3000).map(|i| [1.0, i as f64 * 0.5]).collect();
        let clustered: Vec<Point> = (0..100_000)
            .map(|i| {
                let c = (i % 5) as f64;
                [c + 1e-9 * unit(), c * c + 1e-9 * unit()]
            })
            .collect();
        for points in [&uniform, &grid, &line, &clustered, &uniform[..10].to_vec()] {
            for (seed, growth) in [(1u64, 3u32), (42, 1)] {
                assert_eq!(
                    rounds_in_hilbert_order(points, seed, growth),
                    rounds_in_hilbert_order_by_passes(points, seed, growth),
                    "{} points",
                    points.len()
                );
            }
        }
    }

    /// The points that travel with the words are the points of the order, ties, small buckets
    /// and one bucket holding everything included.
    #[test]
    fn points_travel_with_their_order() {
        let mut s = 5;
        let mut unit = || splitmix64(&mut s) as f64 / u64::MAX as f64;
        let uniform: Vec<Point> = (0..100_000).map(|_| [unit(), unit()]).collect();
        let grid: Vec<Point> = (0..20_000)
            .map(|i| [(i % 37) as f64, ((i * 7) % 23) as f64])
            .collect();
        let clustered: Vec<Point> = (0..30_000)
            .map(|i| [1.0 + 1e-12 * (i % 1000) as f64, 2.0])
            .collect();
        for points in [&uniform, &grid, &clustered, &uniform[..70].to_vec()] {
            for (order, sorted) in [
                multiscale_order_and_points(points, None),
                brio_order_and_points(
                    points,
                    42,
                    Some(&mut vec![MaybeUninit::new(7); 2 * points.len()]),
                ),
            ] {
                let gathered: Vec<Point> = order.iter().map(|&v| points[v as usize]).collect();
                assert_eq!(sorted, gathered);
            }
            assert_eq!(
                multiscale_order_and_points(points, None).0,
                multiscale_order(points)
            );
            assert_eq!(
                brio_order_and_points(points, 42, None).0,
                brio_order(points, 42)
            );
        }
    }

    /// One side of a split, ordered straight from all the points, is the order of all the points
    /// with the other side left out (each kept point has its round and key among all of them),
    /// and its points travel with it; a side with every point or none is the whole order or
    /// nothing.
    #[test]
    fn a_side_is_the_whole_order_restricted_to_it() {
        let uniform = uniform(60_000, &mut 11);
        let grid = grid(20_000);
        for points in [&uniform, &grid, &uniform[..50].to_vec()] {
            let (whole, _) = multiscale_order_and_points(points, None);
            let split = points[points.len() / 3];
            let sides: [&dyn Fn(Point) -> bool; 4] = [
                &|p: Point| p[0] < split[0] || (p[0] == split[0] && p[1] <= split[1]),
                &|p: Point| !(p[0] < split[0] || (p[0] == split[0] && p[1] <= split[1])),
                &|_| true,
                &|_| false,
            ];
            for keep in sides {
                let mut room = vec![MaybeUninit::new(3u64); 2 * points.len()];
                let (order, sorted) =
                    multiscale_order_and_points_where(points, keep, Some(&mut room));
                let expected: Vec<u32> = whole
                    .iter()
                    .copied()
                    .filter(|&v| keep(points[v as usize]))
                    .collect();
                assert_eq!(order, expected);
                let gathered: Vec<Point> = order.iter().map(|&v| points[v as usize]).collect();
                assert_eq!(sorted, gathered);
            }
        }
    }

    /// Points crowded into one cell of the whole box's grid (a patch 10^-7 wide among points
    /// 10^3 away, and inside it a tighter patch) come in a Hilbert order of their own: in the
    /// last round, the path from each patch point to the next is as short as along a curve
    /// through the patch (about 1.6 widths per √m for m points, against m/2 for the input's
    /// order); the sort agrees with the passes'.
    #[test]
    fn crowded_cells_are_ordered_by_their_own_curve() {
        let mut s = 17;
        let mut unit = || splitmix64(&mut s) as f64 / u64::MAX as f64;
        let mut points: Vec<Point> = vec![[-1e3, -1e3], [1e3, 1e3], [1e3, -1e3]];
        let width = 1e-7;
        for i in 0..40_000 {
            let w = if i % 4 == 0 { width * 1e-6 } else { width };
            points.push([0.3 + w * unit(), 0.1 + w * unit()]);
        }
        let (order, sorted) = multiscale_order_and_points(&points, None);
        let rounds = rounds_by_trailing_zeros(3);
        let last_round =
            |v: u32| round_at(MULTISCALE_SEED, v as usize, &rounds) == ROUNDS as u32 - 1;
        let inner = |p: Point| p[0] < 0.3 + width * 1e-6 && p[1] < 0.1 + width * 1e-6;
        for tight in [false, true] {
            let run: Vec<Point> = order
                .iter()
                .zip(&sorted)
                .filter(|&(&v, &p)| last_round(v) && v >= 3 && inner(p) == tight)
                .map(|(_, &p)| p)
                .collect();
            let path: f64 = run
                .windows(2)
                .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt())
                .sum();
            let side = if tight { width * 1e-6 } else { width };
            let per_width = path / side / (run.len() as f64).sqrt();
            assert!(
                per_width < 3.0,
                "tight {tight}: {per_width:.1} widths per √m"
            );
        }
        assert_eq!(
            order,
            rounds_in_hilbert_order_by_passes(&points, MULTISCALE_SEED, 3)
        );
    }

    /// Crowded runs whose points cannot be told apart (copies of one point), or whose box is
    /// too wide for its width to be a number, end the refinement: the orders are permutations.
    #[test]
    fn crowded_copies_and_huge_boxes_end() {
        let copies: Vec<Point> = (0..5000).map(|i| [(i % 2) as f64, 0.5]).collect();
        let mut huge: Vec<Point> = (0..5000).map(|i| [1e-300 * i as f64, 0.0]).collect();
        huge.extend([[-1.7e308, 1.0], [1.7e308, -1.0]]);
        for points in [copies, huge] {
            for order in [multiscale_order(&points), brio_order(&points, 5)] {
                let mut seen = order.clone();
                seen.sort_unstable();
                assert_eq!(seen, (0..points.len() as u32).collect::<Vec<u32>>());
            }
        }
    }

    #[test]
    fn orders_are_permutations() {
        let mut s = 7;
        let pts: Vec<Point> = (0..1000)
            .map(|_| {
                [
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                ]
            })
            .collect();
        for order in [
            hilbert_order(&pts),
            brio_order(&pts, 42),
            multiscale_order(&pts),
        ] {
            let mut seen = order.clone();
            seen.sort_unstable();
            assert_eq!(seen, (0..1000).collect::<Vec<u32>>());
        }
    }
}
