// How raps-sys gets libraps.
//
// With the `bundled` feature (the default): libraps is compiled from the sources this crate
// carries in native/ (symbolic links into the repository, which `cargo package` turns into
// copies) by driving CMake with std::process::Command, since no crates.io crate is reachable,
// and linked statically, so the program needs no libraps.so. That needs cmake, a C++17 compiler
// and Eigen (Debian: cmake g++ libeigen3-dev). RAPS_CMAKE_ARGS adds arguments to the configure
// step (a compiler launcher, say).
//
// Without it (`default-features = false`): the installed libraps.so, found through RAPS_LIB_DIR
// (CMake sets it to the build tree's library folder) or the linker's default paths. The link
// itself is #[link(name = "raps")] in the generated src/lib.rs; the bundled build turns it
// static from here.
use std::env;
use std::path::PathBuf;
use std::process::Command;

fn main() {
    if env::var_os("CARGO_FEATURE_BUNDLED").is_some() {
        build_bundled();
    } else {
        println!("cargo:rerun-if-env-changed=RAPS_LIB_DIR");
        if let Ok(dir) = env::var("RAPS_LIB_DIR") {
            if !dir.is_empty() {
                println!("cargo:rustc-link-search=native={}", dir);
            }
        }
    }
}

fn build_bundled() {
    let manifest_dir = PathBuf::from(env::var("CARGO_MANIFEST_DIR").expect("CARGO_MANIFEST_DIR"));
    let source = manifest_dir.join("native");
    for part in ["CMakeLists.txt", "cmake", "include", "src"] {
        if !source.join(part).exists() {
            panic!(
                "raps-sys: {} is missing: the bundled build needs the library's sources \
                    (or build with default-features = false to link an installed libraps)",
                source.join(part).display()
            );
        }
        println!("cargo:rerun-if-changed=native/{}", part);
    }
    println!("cargo:rerun-if-env-changed=RAPS_CMAKE_ARGS");
    let build = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR")).join("build");
    let mut configure = Command::new(cmake());
    configure
        .arg("-S")
        .arg(&source)
        .arg("-B")
        .arg(&build)
        .args([
            "-DCMAKE_BUILD_TYPE=Release",
            "-DBUILD_SHARED_LIBS=OFF",
            "-DRAPS_BUILD_TESTS=OFF",
            "-DRAPS_BUILD_SAMPLES=OFF",
            "-DRAPS_BUILD_BENCH=OFF",
            "-DRAPS_BUILD_GLTF=OFF",
        ]);
    if let Ok(extra) = env::var("RAPS_CMAKE_ARGS") {
        configure.args(extra.split_whitespace());
    }
    run(&mut configure);
    let jobs = env::var("NUM_JOBS").unwrap_or_else(|_| "1".to_string());
    run(Command::new(cmake()).arg("--build").arg(&build).args([
        "--target",
        "raps",
        "--parallel",
        &jobs,
    ]));
    println!(
        "cargo:rustc-link-search=native={}",
        build.join("src").display()
    );
    println!("cargo:rustc-link-lib=static=raps");
    // libraps is C++ inside; its other needs (threads, libm) are in every Rust program already.
    println!("cargo:rustc-link-lib=dylib=stdc++");
    // For crates that compile C against the header: DEP_RAPS_INCLUDE.
    println!("cargo:include={}", source.join("include").display());
}

fn cmake() -> String {
    println!("cargo:rerun-if-env-changed=CMAKE");
    env::var("CMAKE").unwrap_or_else(|_| "cmake".to_string())
}

fn run(command: &mut Command) {
    let status = command.status().unwrap_or_else(|error| {
        panic!(
            "raps-sys: cannot run {:?} ({}): the bundled build needs cmake",
            command, error
        )
    });
    if !status.success() {
        panic!("raps-sys: {:?} failed ({})", command, status);
    }
}
