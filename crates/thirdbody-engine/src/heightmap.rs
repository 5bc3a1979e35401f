//! Reading a slider height map from a file: CSV (rows of numbers separated by
//! commas, one row per y, first row at the smallest y) or NPY (a 2-D float64
//! array of shape (ny, nx), rows along y; a 1-D array of n is one row, a line
//! contact's profile). Paths are relative to the case file's
//! folder. The heights themselves (finite, rectangular) are checked by the library.

use std::path::Path;

use ndarray::ArrayD;
use thirdbody::{Error, HeightMap};

/// Loads `file` (resolved against `base`, the case file's folder) with sample
/// spacing `cell_size`. Read or format errors name `slider.file`.
pub fn load(base: &Path, file: &str, cell_size: f64) -> thirdbody::Result<HeightMap> {
    let path = base.join(file);
    let bad = |why: String| {
        Error::invalid(
            "slider.file",
            format!("\"{}\"", path.display()),
            &format!(
                "a readable CSV (rows of numbers, rows along y) or float64 NPY file, 2-D \
                 for a map, 1-D for a profile ({})",
                why.replace('\n', " ")
            ),
        )
    };
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (nx, ny, heights) = match extension.as_deref() {
        Some("csv") | Some("txt") => read_csv(&path).map_err(bad)?,
        Some("npy") => read_npy(&path).map_err(bad)?,
        _ => return Err(bad("the name must end in .csv or .npy".into())),
    };
    Ok(HeightMap {
        nx,
        ny,
        cell_size,
        heights,
    })
}

fn read_csv(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| e.to_string())?;
    let mut heights = Vec::new();
    let (mut nx, mut ny) = (0, 0);
    for record in reader.records() {
        let record = record.map_err(|e| e.to_string())?;
        for (i, field) in record.iter().enumerate() {
            let value: f64 = field.parse().map_err(|_| {
                format!(
                    "row {}, column {}: \"{field}\" is not a number",
                    ny + 1,
                    i + 1
                )
            })?;
            heights.push(value);
        }
        nx = record.len();
        ny += 1;
    }
    if ny == 0 {
        return Err("the file holds no numbers".into());
    }
    Ok((nx, ny, heights))
}

/// Checks an NPY file's header against its size before anything is allocated: a
/// header may claim any shape (a 138-byte file claiming (1e8, 1e8) made the reader
/// ask for 80 PB). The format (magic, version, header length, a Python dict literal
/// with `'shape': (...)`) is NumPy's NEP 1; only the shape is read here, the full
/// parse is ndarray-npy's.
fn check_npy_size(path: &Path) -> Result<(), String> {
    use std::io::Read;
    let size = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let mut head = Vec::new();
    std::fs::File::open(path)
        .map_err(|e| e.to_string())?
        .take(65_536 + 12)
        .read_to_end(&mut head)
        .map_err(|e| e.to_string())?;
    if head.len() < 10 || &head[..6] != b"\x93NUMPY" {
        return Err("not an NPY file (no \\x93NUMPY magic)".into());
    }
    let (header_len, start) = match head[6] {
        1 => (u16::from_le_bytes([head[8], head[9]]) as usize, 10),
        _ if head.len() >= 12 => (
            u32::from_le_bytes([head[8], head[9], head[10], head[11]]) as usize,
            12,
        ),
        _ => return Err("a truncated NPY header".into()),
    };
    let header = head
        .get(start..start + header_len)
        .map(String::from_utf8_lossy)
        .ok_or("a truncated NPY header")?;
    let shape = header
        .split("'shape':")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .ok_or("an NPY header without a shape")?;
    let mut count: u128 = 1;
    for dim in shape.trim_start().trim_start_matches('(').split(',') {
        let dim = dim.trim();
        if dim.is_empty() {
            continue;
        }
        let n: u128 = dim
            .trim_end_matches('L')
            .parse()
            .map_err(|_| format!("an NPY shape entry {dim:?} that is not a count"))?;
        count = count.saturating_mul(n);
    }
    let data = (size as u128).saturating_sub((start + header_len) as u128);
    if count.saturating_mul(8) > data {
        return Err(format!(
            "its header claims {count} values but the file holds {data} bytes of data"
        ));
    }
    Ok(())
}

fn read_npy(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    check_npy_size(path)?;
    let array: ArrayD<f64> = ndarray_npy::read_npy(path).map_err(|e| e.to_string())?;
    let (nx, ny) = match *array.shape() {
        [n] => (n, 1),
        [ny, nx] => (nx, ny),
        ref other => {
            return Err(format!(
                "an array of {} dimensions (1 for a profile, 2 for a map)",
                other.len()
            ))
        }
    };
    // `iter` visits in logical (row-major) order whatever the memory layout.
    Ok((nx, ny, array.iter().copied().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::{Array1, Array2, Array3};

    #[test]
    fn a_one_dimensional_npy_is_one_row_and_three_dimensions_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let row = Array1::from_iter((0..5).map(f64::from));
        ndarray_npy::write_npy(dir.path().join("p.npy"), &row).unwrap();
        let m = load(dir.path(), "p.npy", 0.5).unwrap();
        assert_eq!((m.nx, m.ny), (5, 1));
        assert_eq!(m.heights, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
        let cube = Array3::<f64>::zeros((2, 2, 2));
        ndarray_npy::write_npy(dir.path().join("c.npy"), &cube).unwrap();
        let e = load(dir.path(), "c.npy", 0.5).unwrap_err().to_string();
        assert!(
            e.contains("slider.file") && e.contains("3 dimensions"),
            "{e}"
        );
    }

    #[test]
    fn csv_rows_run_along_y() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("m.csv"), "# heights\n1, 2, 3\n4,5,6\n").unwrap();
        let m = load(dir.path(), "m.csv", 0.5).unwrap();
        assert_eq!((m.nx, m.ny, m.cell_size), (3, 2, 0.5));
        // Second row (larger y), first column: index j * nx + i = 3.
        assert_eq!(m.heights, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    }

    #[test]
    fn npy_shape_is_ny_by_nx() {
        let dir = tempfile::tempdir().unwrap();
        let a = Array2::from_shape_fn((2, 3), |(j, i)| (10 * j + i) as f64);
        ndarray_npy::write_npy(dir.path().join("m.npy"), &a).unwrap();
        let m = load(dir.path(), "m.npy", 1.0).unwrap();
        assert_eq!((m.nx, m.ny), (3, 2));
        assert_eq!(m.heights[m.nx + 2], 12.0);
    }

    #[test]
    fn an_npy_header_claiming_more_than_the_file_holds_is_refused() {
        // A valid 2 x 3 file, then the same header claiming (100000000, 100000000).
        let dir = tempfile::tempdir().unwrap();
        let a = Array2::from_shape_fn((2, 3), |(j, i)| (10 * j + i) as f64);
        let path = dir.path().join("m.npy");
        ndarray_npy::write_npy(&path, &a).unwrap();
        assert!(check_npy_size(&path).is_ok());
        // A reported 138-byte file: a version-1 header and no data.
        let mut dict =
            "{'descr': '<f8', 'fortran_order': False, 'shape': (100000000, 100000000), }"
                .to_string();
        while (10 + dict.len() + 1) % 64 != 0 {
            dict.push(' ');
        }
        dict.push('\n');
        let mut header_only = b"\x93NUMPY\x01\x00".to_vec();
        header_only.extend_from_slice(&(dict.len() as u16).to_le_bytes());
        header_only.extend_from_slice(dict.as_bytes());
        std::fs::write(dir.path().join("big.npy"), &header_only).unwrap();
        let e = load(dir.path(), "big.npy", 1.0).unwrap_err().to_string();
        assert!(e.contains("slider.file") && e.contains("claims"), "{e}");
    }

    #[test]
    fn unreadable_and_malformed_files_name_the_field() {
        let dir = tempfile::tempdir().unwrap();
        let e = load(dir.path(), "missing.csv", 1.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("slider.file") && e.contains("missing.csv"),
            "{e}"
        );
        std::fs::write(dir.path().join("r.csv"), "1,2\n3\n").unwrap();
        let e = load(dir.path(), "r.csv", 1.0).unwrap_err().to_string();
        assert!(e.contains("slider.file") && !e.contains('\n'), "{e}");
        std::fs::write(dir.path().join("t.csv"), "1,x\n").unwrap();
        let e = load(dir.path(), "t.csv", 1.0).unwrap_err().to_string();
        assert!(e.contains("\"x\" is not a number"), "{e}");
        let e = load(dir.path(), "m.png", 1.0).unwrap_err().to_string();
        assert!(e.contains(".csv or .npy"), "{e}");
    }
}
