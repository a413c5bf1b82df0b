//! Triangle's own example files, from the data directory of the PyPI `triangle` package (read
//! in place at run time, never copied into this repository): [`data_dir`] finds it,
//! [`example_files`] reads every `.poly`, `.node` and `.ele` (with its `.node`, the segments of
//! its `.poly` and its `.area`) as zero-based inputs.

use std::path::{Path, PathBuf};

use triangle_rs::io::files::{read_area, read_ele, read_node, read_poly, NodeFile, PolyFile};

use super::call::MeshInput;
use super::points::Point;

/// Triangle's example files: `TRIANGLE_DATA_DIR`, else the PyPI package's data directory in the
/// repository's `.venv` (`.venv/lib/python3*/site-packages/triangle/data`). Panics with what to
/// do when neither exists: the differential tests must not be skipped.
pub fn data_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("TRIANGLE_DATA_DIR") {
        let dir = PathBuf::from(dir);
        assert!(
            dir.join("la.poly").is_file(),
            "TRIANGLE_DATA_DIR={} holds no la.poly: point it at the data directory of the PyPI \
             `triangle` package",
            dir.display()
        );
        return dir;
    }
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/lib");
    let found = std::fs::read_dir(&lib).ok().and_then(|entries| {
        entries
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with("python3"))
            .map(|e| e.path().join("site-packages/triangle/data"))
            .find(|d| d.join("la.poly").is_file())
    });
    found.unwrap_or_else(|| {
        panic!(
            "Triangle's example files are missing: no {}/python3*/site-packages/triangle/data \
             (run `bash scripts/setup-python.sh`, which installs the PyPI `triangle` package, or \
             set TRIANGLE_DATA_DIR)",
            lib.display()
        )
    })
}

/// What an example file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A `.poly` file with its own vertices: a PSLG.
    Poly,
    /// A `.node` file that is not a mesh's (no `x.1.node`, no Voronoi `x.v.node`): a point set.
    Points,
    /// An `.ele` file: a mesh to refine with `r`; `areas`: it has an `.area` file.
    Mesh { areas: bool },
}

/// One example file, read as a zero-based input.
#[derive(Clone, Debug)]
pub struct ExampleFile {
    /// The file's name (`la.poly`).
    pub name: String,
    pub kind: Kind,
    pub input: MeshInput,
}

fn read_text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn pairs(flat: &[f64]) -> Vec<Point> {
    flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}

fn node_input(node: &NodeFile) -> MeshInput {
    MeshInput {
        points: pairs(&node.points),
        attributes: node.attributes.clone(),
        attribute_count: node.attribute_count,
        markers: node.markers.clone(),
        ..MeshInput::default()
    }
}

/// The segments of `poly` (and their markers) into `input`, numbered from `first` in the file.
fn take_segments(input: &mut MeshInput, poly: &PolyFile, first: i32) {
    input.segments = poly
        .segments
        .chunks_exact(2)
        .map(|s| [s[0] - first, s[1] - first])
        .collect();
    input.segment_markers = poly.segment_markers.clone();
}

/// A `.poly` file with its own vertices as a zero-based input: vertices, segments, holes and
/// regions (also the test shapes of tests/data/shapes/, see [`super::pslg::shape`]).
pub fn poly_input(poly: &PolyFile) -> MeshInput {
    let first = poly.vertices.first_number.unwrap_or(1) as i32;
    let mut input = node_input(&poly.vertices);
    take_segments(&mut input, poly, first);
    input.holes = pairs(&poly.holes);
    input.regions = poly
        .regions
        .chunks_exact(4)
        .map(|r| [r[0], r[1], r[2], r[3]])
        .collect();
    input
}

/// An area switch (`a<x>`) that makes a few hundred triangles of `points`' bounding box; `x` a
/// power of two, which prints exactly in decimals (Triangle reads no exponent notation).
pub fn area_switch(points: &[Point]) -> String {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let area = (hi[0] - lo[0]) * (hi[1] - lo[1]) / 300.0;
    format!("a{}", 2f64.powi(area.log2().floor() as i32))
}

/// The example file called `name` among `files`; panics when it is missing (the differential
/// tests must not be skipped).
pub fn example_named<'f>(files: &'f [ExampleFile], name: &str) -> &'f ExampleFile {
    files
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("{name} is missing from Triangle's examples"))
}

/// Every example file of `dir`, sorted by name.
pub fn example_files(dir: &Path) -> Vec<ExampleFile> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut found = Vec::new();
    for file in &names {
        let path = dir.join(file);
        if file.ends_with(".poly") {
            let poly = read_poly(&read_text(&path), file, true).unwrap_or_else(|e| panic!("{e}"));
            if poly.vertices.point_count() == 0 {
                continue; // the segments of a mesh (`x.1.poly`): read with its `.ele`
            }
            found.push(ExampleFile {
                name: file.clone(),
                kind: Kind::Poly,
                input: poly_input(&poly),
            });
        } else if let Some(base) = file.strip_suffix(".node") {
            let numbered = base
                .rsplit_once('.')
                .is_some_and(|(_, n)| n.chars().all(|c| c.is_ascii_digit()));
            if base.ends_with(".v") || numbered {
                continue; // a Voronoi diagram, or the vertices of a mesh Triangle made
            }
            let node = read_node(&read_text(&path), file).unwrap_or_else(|e| panic!("{e}"));
            found.push(ExampleFile {
                name: file.clone(),
                kind: Kind::Points,
                input: node_input(&node),
            });
        } else if let Some(base) = file.strip_suffix(".ele") {
            found.push(mesh_file(dir, base, &names));
        }
    }
    found
}

/// The mesh `base.ele` with its `.node`, the segments of its `.poly` if there is one, and the
/// bounds of its `.area` if there is one.
fn mesh_file(dir: &Path, base: &str, names: &[String]) -> ExampleFile {
    let node_file = format!("{base}.node");
    let node =
        read_node(&read_text(&dir.join(&node_file)), &node_file).unwrap_or_else(|e| panic!("{e}"));
    let first = node.first_number.unwrap_or(1) as i32;
    let ele_file = format!("{base}.ele");
    let ele =
        read_ele(&read_text(&dir.join(&ele_file)), &ele_file).unwrap_or_else(|e| panic!("{e}"));
    let mut input = node_input(&node);
    input.triangles = ele.triangles.iter().map(|v| v - first).collect();
    input.corners = ele.corners;
    input.triangle_attributes = ele.attributes.clone();
    input.triangle_attribute_count = ele.attribute_count;
    let poly_file = format!("{base}.poly");
    if names.contains(&poly_file) {
        let poly = read_poly(&read_text(&dir.join(&poly_file)), &poly_file, false)
            .unwrap_or_else(|e| panic!("{e}"));
        take_segments(&mut input, &poly, first);
    }
    let area_file = format!("{base}.area");
    let areas = names.contains(&area_file);
    if areas {
        let file = read_area(&read_text(&dir.join(&area_file)), &area_file)
            .unwrap_or_else(|e| panic!("{e}"));
        input.triangle_areas = Some(file.areas);
    }
    ExampleFile {
        name: ele_file,
        kind: Kind::Mesh { areas },
        input,
    }
}
