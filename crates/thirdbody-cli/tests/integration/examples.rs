//! Every case file shipped in `examples/` parses and passes validation, so the
//! README's commands and the paper cases keep working as the schema evolves.

use std::path::Path;

#[test]
fn every_bundled_example_parses_and_validates() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let mut no_maps = |file: &str, _: f64| -> thirdbody::Result<thirdbody::HeightMap> {
            panic!(
                "{}: bundled examples use no height map ({file})",
                path.display()
            )
        };
        let parsed = thirdbody::case_file::parse_case_file(&text, &mut no_maps);
        assert!(
            parsed.is_ok(),
            "{}: {}",
            path.display(),
            parsed.unwrap_err()
        );
        count += 1;
    }
    assert!(count >= 8, "found only {count} examples");
}
