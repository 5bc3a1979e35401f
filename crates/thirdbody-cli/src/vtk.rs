//! VTK XML image data (`.vti`) for ParaView and VisIt: scalar point fields on a
//! regular 3-D lattice (a block of subsurface stresses). Written by hand because no
//! maintained crate writes the XML formats (vtkio's last stable release is from
//! 2021); the format is small: an XML header naming the lattice and its arrays, then
//! the arrays as raw little-endian Float64 in an `<AppendedData encoding="raw">`
//! section, each preceded by its byte count as a UInt64 (`header_type="UInt64"`;
//! VTK XML Formats, "Appended Data Section", Kitware wiki and docs.vtk.org). The
//! offset of each array counts from the first byte after the `_` marker.
//!
//! Point order is VTK's: x fastest, then y, then z, the order of
//! `thirdbody::stress::StressField`. The third axis is the depth z (positive into
//! the body, as everywhere in thirdbody).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{bail, Result};

/// A regular lattice: `dims[0] x dims[1] x dims[2]` points at
/// `origin + (i, j, k) * spacing`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// Points along x, y, z.
    pub dims: [usize; 3],
    /// Position of point (0, 0, 0).
    pub origin: [f64; 3],
    /// Distance between neighbouring points along each axis (> 0).
    pub spacing: [f64; 3],
}

impl Lattice {
    /// The lattice through the given axis positions, each evenly spaced (a single
    /// position gets the spacing `fallback`).
    pub fn from_axes(axes: [&[f64]; 3], fallback: f64) -> Result<Self> {
        let mut dims = [0; 3];
        let mut origin = [0.0; 3];
        let mut spacing = [fallback; 3];
        for (d, axis) in axes.iter().enumerate() {
            let name = ["x", "y", "z"][d];
            if axis.is_empty() {
                bail!("VTK lattice: the {name} axis has no points");
            }
            if axis.iter().any(|v| !v.is_finite()) {
                bail!("VTK lattice: the {name} axis has a value that is not finite");
            }
            dims[d] = axis.len();
            origin[d] = axis[0];
            if axis.len() > 1 {
                let step = (axis[axis.len() - 1] - axis[0]) / (axis.len() - 1) as f64;
                let uneven = axis
                    .iter()
                    .enumerate()
                    .any(|(k, &v)| (v - (axis[0] + k as f64 * step)).abs() > 1e-9 * step.abs());
                if step.is_nan() || step <= 0.0 || uneven {
                    bail!(
                        "VTK image data needs evenly spaced, increasing positions; the {name} \
                         axis is not"
                    );
                }
                spacing[d] = step;
            }
        }
        if !(fallback.is_finite() && fallback > 0.0) {
            bail!("VTK lattice: the spacing for a single point must be > 0");
        }
        Ok(Lattice {
            dims,
            origin,
            spacing,
        })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.dims.iter().product()
    }

    /// Whether the lattice has no points.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Writes named scalar point fields (each `lattice.len()` values, x fastest) as a
/// `.vti` file.
pub fn write_image_data(path: &Path, lattice: &Lattice, fields: &[(&str, &[f64])]) -> Result<()> {
    if fields.is_empty() {
        bail!("VTK image data: no fields to write");
    }
    for (name, values) in fields {
        if values.len() != lattice.len() {
            bail!(
                "VTK field {name} has {} values; the lattice has {} points",
                values.len(),
                lattice.len()
            );
        }
        if name.is_empty() || name.contains(['"', '<', '>', '&']) {
            bail!("VTK field name {name:?} must be non-empty plain text");
        }
    }
    let [nx, ny, nz] = lattice.dims;
    let extent = format!("0 {} 0 {} 0 {}", nx - 1, ny - 1, nz - 1);
    let triple = |v: [f64; 3]| format!("{} {} {}", v[0], v[1], v[2]);
    let mut w = BufWriter::new(File::create(path)?);
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">"
    )?;
    writeln!(
        w,
        "  <ImageData WholeExtent=\"{extent}\" Origin=\"{}\" Spacing=\"{}\">",
        triple(lattice.origin),
        triple(lattice.spacing)
    )?;
    writeln!(w, "    <Piece Extent=\"{extent}\">")?;
    writeln!(w, "      <PointData Scalars=\"{}\">", fields[0].0)?;
    let bytes_per_array = 8 * lattice.len() as u64;
    for (k, (name, values)) in fields.iter().enumerate() {
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        writeln!(
            w,
            "        <DataArray type=\"Float64\" Name=\"{name}\" format=\"appended\" \
             RangeMin=\"{lo}\" RangeMax=\"{hi}\" offset=\"{}\"/>",
            k as u64 * (8 + bytes_per_array)
        )?;
    }
    writeln!(w, "      </PointData>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </ImageData>")?;
    write!(w, "  <AppendedData encoding=\"raw\">\n   _")?;
    for (_, values) in fields {
        w.write_all(&bytes_per_array.to_le_bytes())?;
        for v in values.iter() {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    writeln!(w, "\n  </AppendedData>")?;
    writeln!(w, "</VTKFile>")?;
    w.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads a file written by [`write_image_data`] back, independently of the
    /// writer: the header's attributes by text search, the arrays at their offsets.
    fn read_back(path: &Path) -> (String, Vec<(String, Vec<f64>)>) {
        let bytes = std::fs::read(path).unwrap();
        let marker = b"<AppendedData encoding=\"raw\">";
        let start = bytes
            .windows(marker.len())
            .position(|w| w == marker)
            .unwrap();
        let header = String::from_utf8(bytes[..start].to_vec()).unwrap();
        let underscore = start + bytes[start..].iter().position(|&b| b == b'_').unwrap();
        let data = &bytes[underscore + 1..];
        let mut arrays = Vec::new();
        for line in header.lines().filter(|l| l.contains("<DataArray")) {
            let attr = |key: &str| {
                let from = line.find(&format!("{key}=\"")).unwrap() + key.len() + 2;
                line[from..].split('"').next().unwrap().to_string()
            };
            let offset: usize = attr("offset").parse().unwrap();
            let count = u64::from_le_bytes(data[offset..offset + 8].try_into().unwrap()) as usize;
            let values = data[offset + 8..offset + 8 + count]
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect();
            arrays.push((attr("Name"), values));
        }
        let tail = String::from_utf8_lossy(&data[data.len() - 40..]).to_string();
        assert!(
            tail.trim_end().ends_with("</AppendedData>\n</VTKFile>"),
            "{tail}"
        );
        (header, arrays)
    }

    #[test]
    fn arrays_round_trip_at_their_offsets() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("block.vti");
        let xs = [-0.5, 0.0, 0.5];
        let ys = [1.0, 2.0];
        let zs = [0.0, 0.25, 0.5, 0.75];
        let lattice = Lattice::from_axes([&xs, &ys, &zs], 1.0).unwrap();
        assert_eq!(lattice.dims, [3, 2, 4]);
        assert_eq!(lattice.spacing, [0.5, 1.0, 0.25]);
        let a: Vec<f64> = (0..24).map(|k| k as f64 * 0.5 - 3.0).collect();
        let b: Vec<f64> = (0..24).map(|k| (k as f64).sin()).collect();
        write_image_data(&path, &lattice, &[("sigma_x", &a), ("tau1", &b)]).unwrap();
        let (header, arrays) = read_back(&path);
        assert!(header.contains("WholeExtent=\"0 2 0 1 0 3\""), "{header}");
        assert!(header.contains("Origin=\"-0.5 1 0\""), "{header}");
        assert!(header.contains("Spacing=\"0.5 1 0.25\""), "{header}");
        assert!(
            header.contains("RangeMin=\"-3\" RangeMax=\"8.5\""),
            "{header}"
        );
        assert_eq!(arrays.len(), 2);
        assert_eq!(arrays[0], ("sigma_x".to_string(), a));
        assert_eq!(arrays[1], ("tau1".to_string(), b));
    }

    #[test]
    fn uneven_axes_and_mismatched_fields_are_refused() {
        let e = Lattice::from_axes([&[0.0, 1.0], &[0.0, 1.0], &[0.0, 0.1, 0.5]], 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("z axis"), "{e}");
        let lattice = Lattice::from_axes([&[0.0, 1.0], &[0.0], &[0.0]], 0.1).unwrap();
        assert_eq!(lattice.spacing, [1.0, 0.1, 0.1]);
        let dir = tempfile::tempdir().unwrap();
        let e = write_image_data(&dir.path().join("x.vti"), &lattice, &[("a", &[1.0])])
            .unwrap_err()
            .to_string();
        assert!(e.contains("1 values") && e.contains("2 points"), "{e}");
    }
}
