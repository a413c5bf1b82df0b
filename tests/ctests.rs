//! Compiles the C programs in `ctests/` against `include/triangle_rs.h` with the `cc` crate, links
//! them to the `libtriangle_rs.so` that cargo built for this test run, runs them and checks their
//! exit code and output. With valgrind installed, `basic` also runs under valgrind's leak checker
//! (the error paths must not leak).

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn manifest_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `target/<profile>`: this test binary lives in `target/<profile>/deps`.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>")
        .to_path_buf()
}

/// The shared library of this source tree: `cargo build --lib` always runs (a no-op when the
/// library is fresh), since cargo does not rebuild the `cdylib` for an integration test and a stale
/// one would miss new symbols.
fn library_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = profile_dir();
        let library = dir.join(format!(
            "{}triangle_rs{}",
            std::env::consts::DLL_PREFIX,
            std::env::consts::DLL_SUFFIX
        ));
        {
            let profile = dir
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or("debug")
                .to_string();
            let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
            let mut build = Command::new(cargo);
            build
                .current_dir(manifest_dir())
                .args(["build", "--lib", "--profile"]);
            build.arg(if profile == "debug" {
                "dev"
            } else {
                profile.as_str()
            });
            if let Some(target_dir) = dir.parent() {
                build.arg("--target-dir").arg(target_dir);
            }
            let status = build.status().expect("run cargo build --lib");
            assert!(status.success(), "cargo build --lib failed");
        }
        assert!(library.exists(), "{} does not exist", library.display());
        dir
    })
}

fn host_triple() -> String {
    let arch = std::env::consts::ARCH;
    match std::env::consts::OS {
        "linux" => format!("{arch}-unknown-linux-gnu"),
        "macos" => format!("{arch}-apple-darwin"),
        os => format!("{arch}-unknown-{os}"),
    }
}

/// Compiles and links `sources` (in `ctests/`) into an executable, with `defines`.
fn compile(name: &str, sources: &[&str], defines: &[&str]) -> PathBuf {
    let out_dir = profile_dir().join("ctests");
    std::fs::create_dir_all(&out_dir).expect("create the ctests output directory");
    let triple = host_triple();
    let compiler = cc::Build::new()
        .target(&triple)
        .host(&triple)
        .opt_level(1)
        .debug(true)
        .out_dir(&out_dir)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .try_get_compiler()
        .expect("a C compiler");
    let exe = out_dir.join(name);
    let lib_dir = library_dir();
    let mut command = compiler.to_command();
    command
        .args([
            "-std=gnu11",
            "-Wall",
            "-Wextra",
            "-Werror=implicit-function-declaration",
        ])
        .arg("-Werror=incompatible-pointer-types")
        .arg("-Werror=int-conversion")
        .arg("-I")
        .arg(manifest_dir().join("include"))
        .arg("-I")
        .arg(manifest_dir().join("ctests"));
    for define in defines {
        command.arg(format!("-D{define}"));
    }
    for source in sources {
        command.arg(manifest_dir().join("ctests").join(source));
    }
    command
        .arg("-o")
        .arg(&exe)
        .arg("-L")
        .arg(lib_dir)
        .arg("-ltriangle_rs")
        .arg(format!("-Wl,-rpath,{}", lib_dir.display()))
        .args(["-lm", "-pthread"]);
    let output = command.output().expect("run the C compiler");
    assert!(
        output.status.success(),
        "compiling {name} failed: {command:?}\n{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    exe
}

fn run(exe: &Path, args: &[&str]) -> Output {
    Command::new(exe)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("run {}: {e}", exe.display()))
}

fn describe(output: &Output) -> String {
    format!(
        "exit {:?}\n--- stdout ---\n{}--- stderr ---\n{}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// Exit 0 passes.
fn assert_passed(name: &str, output: &Output) {
    assert!(
        output.status.success(),
        "{name} failed:\n{}",
        describe(output)
    );
}

#[test]
fn layout_matches_triangle() {
    let debian_header = Path::new("/usr/include/triangle.h");
    let exe = if debian_header.exists() {
        compile(
            "layout",
            &["layout.c", "layout_debian.c"],
            &["HAVE_DEBIAN_TRIANGLE_H"],
        )
    } else {
        common::reference_missing("/usr/include/triangle.h");
        compile("layout-own", &["layout.c"], &[])
    };
    let output = run(&exe, &[]);
    assert!(
        output.status.success(),
        "layout differs:\n{}",
        describe(&output)
    );
}

#[test]
fn basic_calls_outputs_and_error_paths() {
    let exe = compile("basic", &["basic.c"], &[]);
    let output = run(&exe, &[]);
    assert_passed("basic", &output);
    // Every call in `basic` passes Q: nothing may be printed.
    assert!(
        output.stdout.is_empty() && output.stderr.is_empty(),
        "Q must silence everything:\n{}",
        describe(&output)
    );

    if which("valgrind").is_some() {
        let output = Command::new("valgrind")
            .args([
                "--quiet",
                "--leak-check=full",
                "--errors-for-leak-kinds=definite,indirect",
            ])
            .args(["--show-leak-kinds=definite,indirect", "--error-exitcode=9"])
            .arg(&exe)
            .output()
            .expect("run valgrind");
        assert_ne!(
            output.status.code(),
            Some(9),
            "valgrind found errors or leaks:\n{}",
            describe(&output)
        );
        assert_passed("basic under valgrind", &output);
    } else {
        eprintln!("valgrind is not installed: the leak check of ctests/basic.c is skipped");
    }

    // Without Q an error is reported (Triangle prints its errors even with Q; we print none then).
    let output = run(&exe, &["loud"]);
    assert!(output.status.success(), "{}", describe(&output));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        text.contains("NULL"),
        "an error without Q must be reported:\n{}",
        describe(&output)
    );
}

#[test]
fn reentrant_calls_from_two_threads() {
    let exe = compile("reentrant", &["reentrant.c"], &[]);
    let output = run(&exe, &[]);
    eprint!("{}", String::from_utf8_lossy(&output.stdout));
    assert_passed("reentrant", &output);
}

fn which(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH")?
        .to_str()?
        .split(':')
        .map(|dir| Path::new(dir).join(program))
        .find(|path| path.is_file())
}
