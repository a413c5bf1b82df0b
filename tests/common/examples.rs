//! Triangle's own example files (`A.poly`, `la.poly`, `face.poly`, `greenland.node`, the shipped
//! `.1` meshes, …), read in place from the data directory of the PyPI `triangle` package that
//! `scripts/setup-python.sh` installs into `.venv` (they are never copied into this repository:
//! Triangle's licence). `TRIANGLE_DATA_DIR` overrides the place. Missing files fail the test with
//! the command that installs them: differential tests on them are never skipped.

use std::path::{Path, PathBuf};

use triangle_rs::io::files::read_node;

use super::call::MeshInput;
use super::pslg::{from_poly_file, Pslg};

/// The data directory of the installed PyPI `triangle` package.
pub fn data_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("TRIANGLE_DATA_DIR") {
        return PathBuf::from(dir);
    }
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/lib");
    let found = std::fs::read_dir(&lib).ok().and_then(|entries| {
        entries
            .filter_map(Result::ok)
            .map(|e| e.path().join("site-packages/triangle/data"))
            .find(|d| d.is_dir())
    });
    found.unwrap_or_else(|| {
        panic!(
            "Triangle's example files not found under {}: run `bash scripts/setup-python.sh` \
             (it installs the PyPI `triangle` package), or set TRIANGLE_DATA_DIR",
            lib.display()
        )
    })
}

/// The example files whose names end with `suffix` (e.g. `.poly`), sorted by name.
pub fn files(suffix: &str) -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(data_dir())
        .expect("the data directory lists")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.to_string_lossy().ends_with(suffix))
        .collect();
    paths.sort();
    assert!(
        !paths.is_empty(),
        "no {suffix} file in {}",
        data_dir().display()
    );
    paths
}

/// The file's name, for messages.
pub fn name(path: &Path) -> String {
    path.file_name().unwrap().to_string_lossy().into_owned()
}

/// An example `.poly` file as a PSLG (zero-based). A `.poly` without vertices (Triangle's
/// output `.poly` files) takes them from the `.node` file of the same name, as Triangle does.
pub fn pslg(path: &Path) -> Pslg {
    let mut pslg = from_poly_file(path, &name(path));
    if pslg.input.points.is_empty() {
        let vertices = points(&path.with_extension("node"));
        pslg.input = MeshInput {
            segments: pslg.input.segments,
            segment_markers: pslg.input.segment_markers,
            holes: pslg.input.holes,
            regions: pslg.input.regions,
            ..vertices
        };
    }
    pslg
}

/// The vertices of an example `.node` file, with their attributes and markers.
pub fn points(path: &Path) -> MeshInput {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let node = read_node(&text, &name(path)).unwrap_or_else(|e| panic!("{e}"));
    MeshInput {
        points: node.points.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        attributes: node.attributes,
        attribute_count: node.attribute_count,
        markers: node.markers,
        ..MeshInput::default()
    }
}
