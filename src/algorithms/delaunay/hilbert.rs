//! The Hilbert curve of the insertion orders: a point's key (its cell's position along the
//! curve over the points' bounding box), and the points' indices sorted by key.

use crate::geometry::Point;

/// Bits per coordinate of the Hilbert curve's grid: 4096² cells, finer than spatial locality
/// needs at any size this crate meets (10^7 uniform points put fewer than one in a cell; points
/// sharing a cell keep their input order). Three table steps per key.
pub(super) const HILBERT_BITS: u32 = 12;

/// The keys fill the top of 32 bits (the words' buckets take the key's top 8 bits).
pub(super) const KEY_SHIFT: u32 = 32 - 2 * HILBERT_BITS;

/// Position of cell `(x, y)` along the Hilbert curve filling a `2^HILBERT_BITS` square grid.
///
/// Four bits of each coordinate at a time through [`HILBERT_TABLE`]: no branches, whose
/// outcomes (the coordinates' bits) would be unpredictable. The orientation is carried as the
/// table entry's high bits, which are the offset of its quarter of the table: one mask per
/// level, and no bounds check (the index is below 1024 by its bits).
fn hilbert_index(x: u32, y: u32) -> u32 {
    let mut d: u32 = 0;
    let mut quarter = 0u32;
    let mut shift = HILBERT_BITS;
    while shift > 0 {
        shift -= 4;
        let cell = ((x >> shift) & 15) << 4 | ((y >> shift) & 15);
        let entry = u32::from(HILBERT_TABLE[(quarter | cell) as usize]);
        d = (d << 8) | (entry & 0xff);
        quarter = entry & 0x300;
    }
    d
}

/// The Hilbert curve one level (one bit of x and y) at a time: the sub-square's orientation is
/// one of four transformations of the cell coordinates — 0: as is, 1: transposed (x and y
/// swapped), 2: anti-transposed (swapped and complemented), 3: both complemented (turned by
/// 180°). In the sub-square's frame, quadrant (rx, ry) comes at position (3·rx) xor ry, and
/// the next level is transposed when ry = 0 and rx = 0, anti-transposed when ry = 0 and rx = 1.
/// Returns (position, next orientation).
const fn hilbert_step(state: usize, bx: u32, by: u32) -> (u32, usize) {
    let (rx, ry) = match state {
        0 => (bx, by),
        1 => (by, bx),
        2 => (1 - by, 1 - bx),
        _ => (1 - bx, 1 - by),
    };
    // Composing the orientation with a transposition or an anti-transposition.
    const TRANSPOSED: [usize; 4] = [1, 0, 3, 2];
    const ANTI_TRANSPOSED: [usize; 4] = [2, 3, 0, 1];
    let next = match (rx, ry) {
        (0, 0) => TRANSPOSED[state],
        (1, 0) => ANTI_TRANSPOSED[state],
        _ => state,
    };
    ((3 * rx) ^ ry, next)
}

/// Four levels of [`hilbert_step`] at once: at 256 · orientation + 16 · (4 bits of x) + (4
/// bits of y), the 8 bits of position (low byte) and 256 · the orientation after them.
const HILBERT_TABLE: [u16; 1024] = {
    let mut table = [0u16; 1024];
    let mut start = 0;
    while start < 4 {
        let mut xy = 0;
        while xy < 256 {
            let (mut state, mut d, mut level) = (start, 0u32, 4);
            while level > 0 {
                level -= 1;
                let (digit, next) = hilbert_step(
                    state,
                    (xy as u32 >> (4 + level)) & 1,
                    (xy as u32 >> level) & 1,
                );
                d = (d << 2) | digit;
                state = next;
            }
            table[256 * start + xy] = (d as u16) | ((state as u16) << 8);
            xy += 1;
        }
        start += 1;
    }
    table
};

/// The Hilbert-curve key of each point over the points' bounding box, as a function of the point.
pub(super) fn hilbert_key_of(points: &[Point]) -> impl Fn(Point) -> u32 {
    let (mut xmin, mut ymin, mut xmax, mut ymax) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in points {
        xmin = xmin.min(p[0]);
        xmax = xmax.max(p[0]);
        ymin = ymin.min(p[1]);
        ymax = ymax.max(p[1]);
    }
    let cells = ((1u32 << HILBERT_BITS) - 1) as f64;
    let scale_x = if xmax > xmin {
        cells / (xmax - xmin)
    } else {
        0.0
    };
    let scale_y = if ymax > ymin {
        cells / (ymax - ymin)
    } else {
        0.0
    };
    move |p: Point| {
        let x = ((p[0] - xmin) * scale_x) as u32;
        let y = ((p[1] - ymin) * scale_y) as u32;
        hilbert_index(x.min(cells as u32), y.min(cells as u32)) << KEY_SHIFT
    }
}

/// Every point's Hilbert-curve key (over the points' bounding box) in the high half of a word
/// whose low half is the point's index.
fn hilbert_keyed_indices(points: &[Point]) -> Vec<u64> {
    let key = hilbert_key_of(points);
    points
        .iter()
        .enumerate()
        .map(|(i, &p)| (u64::from(key(p)) << 32) | i as u64)
        .collect()
}

/// The points' indices with their Hilbert keys, sorted by key (among points with equal keys the
/// earlier input point first): the index is each word's low half.
pub(super) fn hilbert_sorted_keys(points: &[Point]) -> Vec<u64> {
    radix_sort_by_high_half(hilbert_keyed_indices(points))
}

/// Sorts words whose low halves are already increasing by their high halves, keeping the
/// order of equal high halves (so the result is the plain sorted order). A least-significant-
/// digit radix sort (three stable counting passes of 11, 11 and 10 bits) is linear, and at 10^6
/// keys several times faster than a comparison sort.
fn radix_sort_by_high_half(mut keys: Vec<u64>) -> Vec<u64> {
    const PASSES: [(u32, u32); 3] = [(32, 11), (43, 11), (54, 10)];
    if keys.len() < 1 << 10 {
        keys.sort_unstable();
        return keys;
    }
    let mut counts = [[0usize; 1 << 11]; 3];
    for &k in &keys {
        for (pass, &(shift, bits)) in PASSES.iter().enumerate() {
            counts[pass][((k >> shift) & ((1 << bits) - 1)) as usize] += 1;
        }
    }
    let mut other = vec![0u64; keys.len()];
    for (pass, &(shift, bits)) in PASSES.iter().enumerate() {
        let counts = &mut counts[pass];
        if counts.contains(&keys.len()) {
            continue; // one digit value for all keys: this pass would not move anything
        }
        let mut start = 0;
        for c in counts.iter_mut() {
            let n = *c;
            *c = start;
            start += n;
        }
        for &k in &keys {
            let digit = ((k >> shift) & ((1 << bits) - 1)) as usize;
            other[counts[digit]] = k;
            counts[digit] += 1;
        }
        std::mem::swap(&mut keys, &mut other);
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::delaunay::order::splitmix64;

    #[test]
    fn hilbert_curve_visits_neighbouring_cells() {
        // Consecutive positions are adjacent cells: in the first 64×64 sub-square (which the
        // curve fills before leaving it), and on the coarse grid of 16×16 blocks of 4096² cells.
        for (n, scale) in [(64u32, 0u32), (16, HILBERT_BITS - 4)] {
            let mut by_position = vec![(0u32, 0u32); (n * n) as usize];
            for x in 0..n {
                for y in 0..n {
                    let d = hilbert_index(x << scale, y << scale) >> (2 * scale);
                    assert!(d < n * n, "cells of the first sub-square come first");
                    by_position[d as usize] = (x, y);
                }
            }
            for w in by_position.windows(2) {
                let dist = w[0].0.abs_diff(w[1].0) + w[0].1.abs_diff(w[1].1);
                assert_eq!(dist, 1, "{w:?}");
            }
        }
    }

    #[test]
    fn radix_sort_sorts() {
        let mut s = 3;
        for n in [0usize, 5, 1000, 5000, 100_000] {
            // Few distinct high halves (ties) and a full range, with increasing low halves.
            for spread in [7u64, u32::MAX as u64] {
                let keys: Vec<u64> = (0..n as u64)
                    .map(|i| ((splitmix64(&mut s) % (spread + 1)) << 32) | i)
                    .collect();
                let mut expected = keys.clone();
                expected.sort_unstable();
                assert_eq!(radix_sort_by_high_half(keys), expected);
            }
        }
    }
}
