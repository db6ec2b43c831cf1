// Where to find libraps: RAPS_LIB_DIR (CMake sets it to the build tree's library folder), else
// the linker's default paths (an installed libraps). The link itself is #[link(name = "raps")]
// in the generated src/lib.rs. Nothing is downloaded or built here.
fn main() {
    println!("cargo:rerun-if-env-changed=RAPS_LIB_DIR");
    if let Ok(dir) = std::env::var("RAPS_LIB_DIR") {
        if !dir.is_empty() {
            println!("cargo:rustc-link-search=native={}", dir);
        }
    }
}
