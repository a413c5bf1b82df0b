//! Helpers shared by the command-line tests: temporary directories, running `triangle-rs` and the
//! reference `/usr/bin/triangle`, generated inputs, and order-independent views of output files
//! for comparing two programs' results.
#![allow(dead_code)] // Each test file uses a different part.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use triangle_rs::io::files::{self, EleFile, NodeFile};

/// A directory under the system's temporary directory, removed when dropped.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path =
            std::env::temp_dir().join(format!("triangle-rs-cli-{}-{tag}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create a temporary directory");
        TempDir(path)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }

    pub fn write(&self, name: &str, text: &str) {
        std::fs::write(self.0.join(name), text).expect("write a test input");
    }

    pub fn read(&self, name: &str) -> String {
        std::fs::read_to_string(self.0.join(name)).unwrap_or_else(|e| panic!("read {name}: {e}"))
    }

    pub fn exists(&self, name: &str) -> bool {
        self.0.join(name).exists()
    }

    /// The names of the files in the directory.
    pub fn files(&self) -> BTreeSet<String> {
        std::fs::read_dir(&self.0)
            .expect("list a temporary directory")
            .map(|e| {
                e.expect("directory entry")
                    .file_name()
                    .to_string_lossy()
                    .into_owned()
            })
            .collect()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Our binary, built by cargo for the integration tests.
pub fn ours() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_triangle-rs"))
}

/// Debian's `triangle`, or `None` (with a message) when it is not installed; on CI (env `CI`
/// set) a missing reference is a failure, so differential tests cannot silently pass.
pub fn reference() -> Option<PathBuf> {
    let path = PathBuf::from("/usr/bin/triangle");
    if path.is_file() {
        return Some(path);
    }
    if std::env::var_os("CI").is_some() {
        panic!("/usr/bin/triangle is missing and CI is set: install Debian's triangle-bin (see .ci/run)");
    }
    eprintln!("SKIPPED: /usr/bin/triangle is not installed (apt-get install triangle-bin); differential test not run");
    None
}

/// What a program run gave.
pub struct Run {
    pub status: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    pub fn ok(&self) -> bool {
        self.status == Some(0)
    }
}

pub fn run(program: &Path, dir: &Path, args: &[&str]) -> Run {
    let output = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("run {}: {e}", program.display()));
    Run {
        status: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// A hand-written input file from tests/data.
pub fn data(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()))
}

/// A deterministic pseudo-random generator (64-bit LCG), so inputs are the same on every run.
pub struct Lcg(u64);

impl Lcg {
    pub fn new(seed: u64) -> Lcg {
        Lcg(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(1))
    }
    /// A value in [0, 1) with 53 random bits.
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A `.node` file of `n` random vertices in general position (full-precision coordinates),
/// with `attributes` attributes and, if `markers`, a marker column (every fifth vertex marked).
pub fn random_node_file(
    seed: u64,
    n: usize,
    attributes: usize,
    markers: bool,
    first_index: usize,
) -> String {
    let mut rng = Lcg::new(seed);
    let mut text = format!(
        "# {n} random vertices (seed {seed})\n{n} 2 {attributes} {}\n",
        markers as u8
    );
    for i in 0..n {
        let (x, y) = (rng.next() * 10.0 - 5.0, rng.next() * 7.0);
        text.push_str(&format!("{} {x:e} {y}", i + first_index));
        for _ in 0..attributes {
            text.push_str(&format!(" {}", rng.next() * 100.0));
        }
        if markers {
            text.push_str(&format!(
                " {}",
                if i % 5 == 0 { (i % 3) as i32 + 2 } else { 0 }
            ));
        }
        text.push('\n');
    }
    text
}

// ------------------------------------------------------------------------------------------------
// Order-independent views of output files

/// A vertex identified by its exact coordinates (with -0.0 read as 0.0).
pub type Point = (u64, u64);

pub fn point_key(x: f64, y: f64) -> Point {
    ((x + 0.0).to_bits(), (y + 0.0).to_bits())
}

pub fn point_value(p: Point) -> (f64, f64) {
    (f64::from_bits(p.0), f64::from_bits(p.1))
}

/// One program's results in a directory, parsed.
pub struct Results {
    pub node: NodeFile,
    pub first_index: i32,
}

impl Results {
    /// Reads `<base>.node` in `dir`; the numbering base is that of the first vertex.
    pub fn read(dir: &TempDir, node_file: &str) -> Results {
        let node =
            files::read_node(&dir.read(node_file), node_file).expect("parse the .node output");
        let first_index = node.first_number.unwrap_or(1) as i32;
        Results { node, first_index }
    }

    pub fn point(&self, v: i32) -> Point {
        let i = usize::try_from(v - self.first_index)
            .unwrap_or_else(|_| panic!("vertex {v} below the base"));
        point_key(self.node.points[2 * i], self.node.points[2 * i + 1])
    }

    /// The triangles as corner coordinates (first three corners), each rotated so that its
    /// smallest corner comes first (orientation is kept), with the other nodes and attributes.
    pub fn triangles(&self, ele: &EleFile) -> Vec<CanonicalTriangle> {
        (0..ele.triangle_count())
            .map(|t| {
                let nodes = &ele.triangles[t * ele.corners..(t + 1) * ele.corners];
                let corners = [
                    self.point(nodes[0]),
                    self.point(nodes[1]),
                    self.point(nodes[2]),
                ];
                let r = (0..3).min_by_key(|&k| corners[k]).unwrap();
                let rotated = [corners[r], corners[(r + 1) % 3], corners[(r + 2) % 3]];
                // Second-order nodes follow their opposite corners.
                let extra: Vec<Point> = if ele.corners == 6 {
                    let mids = [
                        self.point(nodes[3]),
                        self.point(nodes[4]),
                        self.point(nodes[5]),
                    ];
                    vec![mids[r], mids[(r + 1) % 3], mids[(r + 2) % 3]]
                } else {
                    Vec::new()
                };
                let attributes = ele.attributes
                    [t * ele.attribute_count..(t + 1) * ele.attribute_count]
                    .iter()
                    .map(|a| a.to_bits())
                    .collect();
                CanonicalTriangle {
                    corners: rotated,
                    extra,
                    attributes,
                    rotation: r,
                }
            })
            .collect()
    }
}

#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct CanonicalTriangle {
    pub corners: [Point; 3],
    pub extra: Vec<Point>,
    pub attributes: Vec<u64>,
    /// How far the corners were rotated (to rotate per-corner data the same way).
    pub rotation: usize,
}

impl CanonicalTriangle {
    /// The corners alone, as a sortable key.
    pub fn key(&self) -> [Point; 3] {
        self.corners
    }
}

/// Sorted triangles without the rotation bookkeeping, for set comparisons.
pub fn triangle_set(triangles: &[CanonicalTriangle]) -> Vec<(Vec<Point>, Vec<u64>)> {
    let mut set: Vec<(Vec<Point>, Vec<u64>)> = triangles
        .iter()
        .map(|t| {
            let mut nodes = t.corners.to_vec();
            nodes.extend_from_slice(&t.extra);
            (nodes, t.attributes.clone())
        })
        .collect();
    set.sort();
    set
}

/// An unordered edge by coordinates.
pub fn edge_key(a: Point, b: Point) -> (Point, Point) {
    if a <= b {
        (a, b)
    } else {
        (b, a)
    }
}

/// Signed area of a triangle of points (positive when counterclockwise).
pub fn signed_area(t: &[Point; 3]) -> f64 {
    let [a, b, c] = t.map(point_value);
    0.5 * ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0))
}

/// The smallest angle of a triangle, in degrees.
pub fn smallest_angle(t: &[Point; 3]) -> f64 {
    let p = t.map(point_value);
    (0..3)
        .map(|k| {
            let (a, b, c) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            let (u, v) = ((b.0 - a.0, b.1 - a.1), (c.0 - a.0, c.1 - a.1));
            (u.0 * v.1 - u.1 * v.0)
                .abs()
                .atan2(u.0 * v.0 + u.1 * v.1)
                .to_degrees()
        })
        .fold(180.0, f64::min)
}

/// `a` and `b` agree to a relative tolerance `tolerance` (absolute near 0).
pub fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1.0)
}

/// Lines of a file without its last `# Generated by` line, which names the program.
pub fn without_footer(text: &str) -> Vec<&str> {
    let mut lines: Vec<&str> = text.lines().collect();
    assert!(
        lines
            .last()
            .is_some_and(|l| l.starts_with("# Generated by ")),
        "the file does not end with a `# Generated by` line:\n{text}"
    );
    lines.pop();
    lines
}
