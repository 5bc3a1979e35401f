//! The bundled example case files (`examples/<name>.toml` at the repository's root)
//! with another cell count: shared by the tests, benches and examples of the library
//! crate (included with `#[path]` where it is not a test).

use thirdbody::{Case, HeightMap, Result};

/// `examples/<name>.toml` with `n x n` cells.
pub fn bundled(name: &str, n: usize) -> Case {
    let path = format!("{}/../../examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("bundled example");
    let mut no_maps = |_: &str, _: f64| -> Result<HeightMap> { unreachable!("no height map") };
    let mut case = thirdbody::case_file::parse_case_file(&text, &mut no_maps)
        .expect("valid example")
        .case;
    case.grid.cells = [n, n];
    case
}
