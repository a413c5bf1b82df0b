//! The checked-in C header `include/triangle_rs.h` is exactly what cbindgen generates from the
//! crate with `cbindgen.toml`. Run with `UPDATE_HEADER=1` to rewrite it after changing the ABI.

use std::path::Path;

fn generate_header() -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config =
        cbindgen::Config::from_file(root.join("cbindgen.toml")).expect("cbindgen.toml parses");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(root.join("src/lib.rs"))
        .generate()
        .expect("cbindgen generates the header");
    let mut bytes = Vec::new();
    bindings.write(&mut bytes);
    String::from_utf8(bytes).expect("the header is UTF-8")
}

#[test]
fn checked_in_header_matches_generated() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/triangle_rs.h");
    let generated = generate_header();
    if std::env::var_os("UPDATE_HEADER").is_some_and(|v| v == "1") {
        std::fs::write(&path, &generated).expect("write include/triangle_rs.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/triangle_rs.h is out of date: regenerate it with `UPDATE_HEADER=1 cargo test --test header`.\n\
         --- generated ---\n{generated}"
    );
}

#[test]
fn header_declares_the_triangle_abi() {
    // What C code written for Triangle relies on, independent of formatting.
    let header = generate_header();
    for needle in [
        "struct triangulateio {",
        "double *pointlist;",
        "int *pointmarkerlist;",
        "int numberofpoints;",
        "double *normlist;",
        "int numberofedges;",
        "int triangulate(const char *switches,",
        "struct triangulateio *in,",
        "void trifree(void *memptr);",
        "int triangulate_catch_exit(",
        "void triunsuitable_callback(",
        "int triangulate_reentrant(",
        "const char *triangulate_last_error(void);",
        "#ifdef __cplusplus",
        "extern \"C\" {",
        "#ifndef TRIANGLE_RS_H",
    ] {
        assert!(
            header.contains(needle),
            "the generated header lacks `{needle}`:\n{header}"
        );
    }
    assert!(
        !header.contains("typedef struct"),
        "the struct must be a plain tag, as in Triangle's header"
    );
}

#[test]
fn header_declares_every_exported_function() {
    // Every `#[no_mangle] extern "C" fn` of src/ffi.rs is declared (including the ones that
    // cbindgen.toml declares by hand).
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ffi = std::fs::read_to_string(root.join("src/ffi.rs")).expect("read src/ffi.rs");
    let header =
        std::fs::read_to_string(root.join("include/triangle_rs.h")).expect("read the header");
    let mut exported = Vec::new();
    let mut after_no_mangle = false;
    for line in ffi.lines().map(str::trim) {
        if line.starts_with("#[no_mangle]") || line.starts_with("#[unsafe(no_mangle)]") {
            after_no_mangle = true;
        } else if after_no_mangle && line.contains("extern \"C\" fn ") {
            let name = line
                .split("fn ")
                .nth(1)
                .and_then(|rest| rest.split('(').next())
                .unwrap_or_default();
            exported.push(name.trim().to_string());
            after_no_mangle = false;
        }
    }
    assert!(exported.len() >= 6, "found only {exported:?} in src/ffi.rs");
    for name in exported {
        let declared = header
            .match_indices(&format!("{name}("))
            .any(|(i, _)| i > 0 && matches!(header.as_bytes()[i - 1], b' ' | b'*'));
        assert!(declared, "include/triangle_rs.h does not declare `{name}`");
    }
}
