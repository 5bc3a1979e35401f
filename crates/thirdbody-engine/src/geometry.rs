//! What a case may ask for given its contact's geometry. A line contact (plane
//! strain) has no y: a stress request that names the y of its XZ plane or a 3-D
//! block (a point contact's map outputs over x and y) is refused before anything
//! runs, with a message naming the key, the same for `thirdbody solve`,
//! `thirdbody stress`, a sweep and Python.

use thirdbody::stress::{SectionKind, StressRequest};
use thirdbody::Case;

/// Refuses what `stress` asks of `case` that its geometry does not have: for a line
/// contact, `stress.y` other than 0 and the `"block"` section.
pub fn check(case: &Case, stress: Option<&StressRequest>) -> Result<(), String> {
    let (true, Some(request)) = (case.slider.is_line(), stress) else {
        return Ok(());
    };
    if request.y != 0.0 {
        return Err(format!(
            "stress.y = {} is not allowed: a line contact (plane strain) has no y; leave \
             stress.y out",
            request.y
        ));
    }
    let asks_block = request
        .sections
        .as_ref()
        .is_some_and(|s| s.contains(&SectionKind::Block));
    if asks_block {
        return Err(
            "stress.sections = block is not allowed: a line contact (plane strain) has no y, \
             so no 3-D block; its XZ section (\"xz\") holds every point"
                .to_string(),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> thirdbody::case_file::CaseFile {
        thirdbody::case_file::parse_case_file(text, &mut |_, _| unreachable!()).unwrap()
    }

    /// The bundled Hertz cases, a line and a point contact.
    const LINE: &str = include_str!("../../../examples/hertz_line.toml");
    const POINT: &str = include_str!("../../../examples/hertz.toml");

    #[test]
    fn a_line_contact_refuses_a_y_and_a_block_naming_the_key() {
        let ok = parse(&format!("{LINE}[stress]\n"));
        assert_eq!(check(&ok.case, ok.stress.as_ref()), Ok(()));
        let y = parse(&format!("{LINE}[stress]\ny = 0.5\n"));
        let e = check(&y.case, y.stress.as_ref()).unwrap_err();
        assert!(
            e.contains("stress.y = 0.5") && e.contains("line contact"),
            "{e}"
        );
        let block = parse(&format!("{LINE}[stress]\nsections = [\"xz\", \"block\"]\n"));
        let e = check(&block.case, block.stress.as_ref()).unwrap_err();
        assert!(e.contains("stress.sections = block"), "{e}");
        // A point contact may ask for both.
        let point = parse(&format!(
            "{POINT}[stress]\ny = 0.5\nsections = [\"xz\", \"block\"]\n"
        ));
        assert_eq!(check(&point.case, point.stress.as_ref()), Ok(()));
    }
}
