//! The fuzz targets' checks (`fuzz/cases.rs`) on stable Rust: seeded random byte strings through
//! each case for a bounded number of cases (and at most `FUZZ_SECONDS`, default 20 per target,
//! so that the suite stays short; the cases run in a fixed order (`FUZZ_SEED` shifts the seeds, for
//! a longer campaign past the cases every run makes), so a failure names its seed and
//! reproduces). A long campaign runs the same cases under libFuzzer: see fuzz/README.md.

#[path = "../fuzz/cases.rs"]
mod cases;
mod common;

use std::time::{Duration, Instant};

use common::rng::SplitMix64;
use common::timing::number_from_env;

/// Runs `case` on random byte strings of up to `max_len` bytes: at most `count` of them, for at
/// most the time budget. Returns how many ran.
fn drive(name: &str, seed: u64, count: usize, max_len: usize, case: impl Fn(&[u8])) -> usize {
    let budget = Duration::from_secs(number_from_env("FUZZ_SECONDS", 20) as u64);
    let start = Instant::now();
    // `FUZZ_SEED` shifts every target's seed, for a campaign past the cases every run makes.
    let seed = seed.wrapping_add(number_from_env("FUZZ_SEED", 0) as u64);
    let mut rng = SplitMix64::new(seed);
    let mut ran = 0;
    while ran < count && start.elapsed() < budget {
        let len = rng.below(max_len + 1);
        let data: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        let case_start = Instant::now();
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| case(&data)));
        if case_start.elapsed() > Duration::from_secs(1) {
            println!(
                "{name}: case {ran} took {:.1} s: {data:?}",
                case_start.elapsed().as_secs_f64()
            );
        }
        if outcome.is_err() {
            panic!("{name}: case {ran} (seed {seed:#x}) failed; bytes {data:?}");
        }
        ran += 1;
    }
    println!(
        "{name}: {ran} cases in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    ran
}

#[test]
fn triangulate_through_the_c_abi() {
    let ran = drive(
        "triangulate",
        0xF022_0001,
        number_from_env("FUZZ_CASES", 20_000),
        160,
        |d| cases::triangulate(d, false),
    );
    assert!(ran > 100, "only {ran} cases ran");
}

#[test]
fn triangulate_extreme_coordinates() {
    let ran = drive(
        "triangulate (extreme)",
        0xF022_0002,
        number_from_env("FUZZ_CASES", 5_000),
        160,
        |d| cases::triangulate(d, true),
    );
    assert!(ran > 100, "only {ran} cases ran");
}

#[test]
fn file_readers() {
    // Readers see text: draw bytes from a small alphabet of what the formats are made of.
    const ALPHABET: &[u8] = b"0123456789 .-+eE#\n\n\n\tnaif1e309";
    let ran = drive("file readers", 0xF022_0003, 20_000, 200, |d| {
        let text: Vec<u8> = d
            .iter()
            .map(|&b| ALPHABET[b as usize % ALPHABET.len()])
            .collect();
        cases::read_files(&text);
        cases::read_files(d);
    });
    assert!(ran > 100, "only {ran} cases ran");
}

#[test]
fn switch_parser() {
    const ALPHABET: &[u8] = b"pqaAcDjevnzYSoiFlsCQVXrIhgBPNEOuwW0123456789.e-+ ";
    let ran = drive("switches", 0xF022_0004, 50_000, 24, |d| {
        let text: Vec<u8> = d
            .iter()
            .map(|&b| ALPHABET[b as usize % ALPHABET.len()])
            .collect();
        cases::parse_switches(&text);
        cases::parse_switches(d);
    });
    assert!(ran > 100, "only {ran} cases ran");
}

/// Case 2 080 084 of seed 0xf0220001 (`Qa0.474q33pDceS20000`): concentric shells near a vertex
/// where a hull segment (`c`) leaves at 56° from an input segment put vertices of both within
/// the chain check's tolerance of either line; the chain is followed with backtracking.
#[test]
fn chains_near_a_vertex_at_the_scale_of_the_smallest_shells() {
    cases::triangulate(
        &[
            230, 129, 180, 52, 35, 107, 91, 133, 234, 27, 31, 139, 83, 236, 87, 65, 124, 36, 82,
            208, 109, 228, 217, 123, 164, 55, 91, 63, 126, 139, 160, 115, 162, 126, 210, 97, 141,
            36, 170, 125, 2, 124, 60, 116, 175, 158, 45, 33, 229, 103, 192, 215, 14, 150, 33, 241,
            33, 138, 181, 174, 14, 43, 46, 60, 227, 152, 104, 181, 52, 235, 230, 117, 22, 68, 22,
            114, 137, 84, 6, 103, 95, 242, 159, 240, 235, 158, 234, 247, 80, 68, 195, 211, 30, 161,
            161, 33, 46, 54, 183, 216, 103, 157, 61, 230, 109, 134, 23, 119, 183, 14, 36, 167, 197,
            3, 28, 134, 80, 168, 154, 146, 76,
        ],
        false,
    );
}
