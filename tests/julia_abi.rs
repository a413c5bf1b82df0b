//! Keeps the Julia package honest on machines without Julia: compiles `ctests/julia_calls.c`
//! (the exact library calls of `julia/src` and of Triangulate.jl, on the cases of Triangulate.jl's
//! test suite) with the `cc` crate, links it to the `libtriangle_rs` cdylib of this test run and
//! runs it. Where the compiler supports AddressSanitizer the program is built with it, so a
//! double free or a leak of the ownership rules (free every output array except
//! `holelist`/`regionlist`) fails the test.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `target/<profile>`: this test binary lives in `target/<profile>/deps`.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test binary>")
        .to_path_buf()
}

fn library_file_name() -> String {
    format!(
        "{}triangle_rs{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    )
}

/// The directory holding the cdylib that cargo built for this run (it builds every crate type of
/// the library for integration tests); built with `cargo build --lib` if it is missing.
fn library_dir() -> PathBuf {
    let dir = profile_dir();
    if !dir.join(library_file_name()).exists() {
        let profile = match dir.file_name().and_then(|name| name.to_str()) {
            Some("debug") | None => "dev".to_string(),
            Some(other) => other.to_string(),
        };
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut build = Command::new(cargo);
        build.current_dir(env!("CARGO_MANIFEST_DIR")).args([
            "build",
            "--lib",
            "--profile",
            &profile,
        ]);
        if let Some(target_dir) = dir.parent() {
            build.arg("--target-dir").arg(target_dir);
        }
        let status = build.status().expect("run cargo build --lib");
        assert!(status.success(), "cargo build --lib failed");
    }
    assert!(
        dir.join(library_file_name()).exists(),
        "no {} in {}",
        library_file_name(),
        dir.display()
    );
    dir
}

fn host_triple() -> String {
    let arch = std::env::consts::ARCH;
    match std::env::consts::OS {
        "linux" => format!("{arch}-unknown-linux-gnu"),
        "macos" => format!("{arch}-apple-darwin"),
        os => format!("{arch}-unknown-{os}"),
    }
}

/// Compiles `ctests/julia_calls.c` into `name`, with AddressSanitizer if asked. `None` if the
/// compiler refused (only tolerated for the sanitizer build).
fn compile(name: &str, sanitize: bool) -> Option<PathBuf> {
    let out_dir = profile_dir().join("julia-abi");
    std::fs::create_dir_all(&out_dir).expect("create the output directory");
    let triple = host_triple();
    let compiler = cc::Build::new()
        .target(&triple)
        .host(&triple)
        .opt_level(1)
        .debug(true)
        .out_dir(&out_dir)
        .cargo_metadata(false)
        .get_compiler();
    let lib_dir = library_dir();
    let exe = out_dir.join(name);
    let mut command = compiler.to_command();
    command
        .args(["-std=c11", "-Wall", "-Wextra", "-pthread"])
        .args([
            "-Werror=implicit-function-declaration",
            "-Werror=incompatible-pointer-types",
        ])
        .arg(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("ctests")
                .join("julia_calls.c"),
        )
        .arg("-o")
        .arg(&exe)
        .arg(format!("-L{}", lib_dir.display()))
        .arg(format!("-Wl,-rpath,{}", lib_dir.display()))
        .args(["-ltriangle_rs", "-lm"]);
    if sanitize {
        command.args(["-fsanitize=address", "-fno-omit-frame-pointer"]);
    }
    let output = command.output().expect("run the C compiler");
    if !output.status.success() {
        let diagnostics = String::from_utf8_lossy(&output.stderr);
        assert!(
            sanitize,
            "compiling ctests/julia_calls.c failed:\n{diagnostics}"
        );
        eprintln!(
            "no AddressSanitizer build ({}); running the plain build",
            diagnostics.lines().next().unwrap_or("")
        );
        return None;
    }
    Some(exe)
}

fn run(exe: &Path, detect_leaks: bool) -> Output {
    Command::new(exe)
        .env(
            "ASAN_OPTIONS",
            format!("detect_leaks={}:abort_on_error=0", u8::from(detect_leaks)),
        )
        .output()
        .expect("run julia_calls")
}

/// Every case of ctests/julia_calls.c, each of which must print `PASS <case>`: the cases of
/// Triangulate.jl's test suite (diamond `paAqQ`, T-shaped `pcDQ`, unit square `pqQn` and
/// `pqo2Q`, two points -> error, point attributes), its example point sets, and the callback.
const CASES: &[&str] = &[
    "diamond paAqQ (test_triangulate)",
    "raw CTriangulateIO paAqQ via triangulate_catch_exit (test_ctriangulate)",
    "T-shaped PSLG pcDQ, no segment markers (test_triangulate2)",
    "two points Q -> TriangulateError (test_triangulate_catch_exit)",
    "two points, raw call returns 1 (test_ctriangulate_catch_exit)",
    "0-based segments -> TriangulateError naming the segment and the range",
    "rpq keeps the holes of the input (refining a mesh of a square with a hole)",
    "unit square pqQn (test_neighbors)",
    "unit square pqQ (test_o2)",
    "unit square pqo2Q (test_o2)",
    "point attributes Q (test_pointattributelist)",
    "point attributes Qa0.05 (test_pointattributelist)",
    "Voronoi diagram vQ (example_pointsets)",
    "convex hull segments cQ (example_pointsets)",
    "triunsuitable! is callable; without u the test is never called",
    "u with a per-call test (triangulate(...; unsuitable))",
    "u with the global triunsuitable_callback (Triangulate.jl unchanged)",
    "u from two threads at once, each with its own test",
    "an exception in the test cancels the call and is rethrown",
    "z is accepted and dropped: pzQ is pQ, indices stay 1-based",
];

#[test]
fn julia_package_calls_work_on_the_library() {
    let (exe, mut output) = match compile("julia_calls_asan", true) {
        Some(exe) => {
            let output = run(&exe, true);
            (exe, output)
        }
        None => {
            let exe = compile("julia_calls", false).expect("plain build");
            let output = run(&exe, false);
            (exe, output)
        }
    };
    if String::from_utf8_lossy(&output.stderr)
        .contains("LeakSanitizer has encountered a fatal error")
    {
        // LeakSanitizer cannot run here (e.g. under ptrace); keep the address checks.
        output = run(&exe, false);
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    println!("{stdout}");
    eprintln!("{stderr}");
    assert!(
        output.status.success(),
        "{} failed ({}):\n{stdout}\n{stderr}",
        exe.display(),
        output.status
    );
    assert!(
        !stdout.lines().any(|line| line.starts_with("FAIL")),
        "a case failed:\n{stdout}"
    );
    // Exactly the listed cases passed, each once, and nothing else was reported.
    let passed: Vec<&str> = stdout
        .lines()
        .filter_map(|line| line.strip_prefix("PASS "))
        .collect();
    assert_eq!(passed, CASES, "not every case passed:\n{stdout}");
    assert!(
        stdout
            .lines()
            .all(|line| line.starts_with("PASS ") || line == "0 failed" || line.is_empty()),
        "unexpected output:\n{stdout}"
    );
}
