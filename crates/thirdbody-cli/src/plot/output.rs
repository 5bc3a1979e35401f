//! Writing a figure to disk: the embedded font, the output format from the file
//! extension (SVG vector, or PNG: that SVG rasterised anti-aliased by resvg, see
//! `write_png`) and the atomic write (render to a temporary file in the same folder,
//! then rename; the temporary is removed on error; see [`crate::atomic`]).

use std::path::Path;
use std::sync::OnceLock;

use anyhow::{anyhow, bail, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// DejaVu Sans (Bitstream Vera licence), embedded so that no system font is needed.
static FONT_BYTES: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Font family every text of the figures uses; the embedded font is registered under it.
pub(crate) const FAMILY: &str = "sans-serif";

/// Registers the embedded font with plotters exactly once; later calls return the first
/// outcome.
fn register_embedded_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT_BYTES).is_ok()
    });
    if ok {
        Ok(())
    } else {
        bail!("the embedded font DejaVuSans.ttf could not be loaded")
    }
}

/// Something that draws itself on a drawing area of any plotters backend.
pub(crate) trait Figure {
    /// Canvas size in pixels (width, height).
    fn size(&self) -> (u32, u32);
    /// Draws the whole figure on `root` (already filled white).
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Converts a plotters drawing error into an anyhow error.
pub(crate) fn draw_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("drawing failed: {e}")
}

#[derive(Clone, Copy)]
enum Format {
    Png,
    Svg,
}

/// Renders `figure` to `path` (PNG or SVG by extension, case-insensitive) atomically.
pub(crate) fn write_figure(path: &Path, figure: &impl Figure) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("png") => Format::Png,
        Some("svg") => Format::Svg,
        _ => bail!(
            "plot file {}: unknown extension, allowed: .png or .svg",
            path.display()
        ),
    };
    register_embedded_font()?;
    // The temporary keeps the extension, so the PNG encoder still recognises the format;
    // the backend may have written (part of) it on drop, and it is removed on error.
    crate::atomic::write_with(path, |tmp| render(tmp, format, figure))
        .with_context(|| format!("writing plot {}", path.display()))
}

fn render(tmp: &Path, format: Format, figure: &impl Figure) -> Result<()> {
    let svg = svg_text(figure)?;
    match format {
        Format::Png => write_png(tmp, &svg, figure.size()),
        Format::Svg => {
            std::fs::write(tmp, svg).with_context(|| format!("writing {}", tmp.display()))
        }
    }
}

/// The figure drawn by plotters' SVG backend, with the raster's media type corrected:
/// plotters 0.3.7 embeds rasters as `data:png;base64,...`, which is not a valid media
/// type (RFC 2397 wants `image/png`) and some SVG readers refuse it.
fn svg_text(figure: &impl Figure) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, figure.size()).into_drawing_area();
        draw_and_present(&root, figure)?;
    }
    Ok(svg.replace("\"data:png;base64,", "\"data:image/png;base64,"))
}

/// Rasterises the SVG text of a figure of `size` pixels to an RGB PNG at `path`.
///
/// Why through SVG: plotters' bitmap backend draws lines without anti-aliasing (edges
/// in steps, widths that change with the slope) and places each glyph at a whole pixel
/// (digits unevenly spaced). resvg (tiny-skia) draws the same SVG anti-aliased and lays
/// out text with the font's advances and kerning, so the PNG and the SVG of a figure
/// are one picture. Supersampling the bitmap backend would need every pixel size of
/// the layout scaled and would still place glyphs by whole (super)pixels. The cost is a
/// few tens of milliseconds per figure.
fn write_png(path: &Path, svg: &str, (w, h): (u32, u32)) -> Result<()> {
    let tree = resvg::usvg::Tree::from_str(svg, svg_options())
        .map_err(|e| anyhow!("reading back the figure's SVG: {e}"))?;
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| anyhow!("a figure of {w} x {h} pixels cannot be rasterised"))?;
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    // Opaque throughout (the white fill): keep the colour channels.
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let file =
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| anyhow!("PNG: {e}"))?;
    writer
        .write_image_data(&rgb)
        .map_err(|e| anyhow!("PNG: {e}"))?;
    writer.finish().map_err(|e| anyhow!("PNG: {e}"))
}

/// The options of the rasteriser: the embedded font as the only one, for the family
/// "sans-serif" the SVG names.
fn svg_options() -> &'static resvg::usvg::Options<'static> {
    static OPTIONS: OnceLock<resvg::usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut fonts = resvg::usvg::fontdb::Database::new();
        fonts.load_font_data(FONT_BYTES.to_vec());
        fonts.set_sans_serif_family("DejaVu Sans");
        resvg::usvg::Options {
            font_family: "DejaVu Sans".into(),
            fontdb: std::sync::Arc::new(fonts),
            ..resvg::usvg::Options::default()
        }
    })
}

fn draw_and_present<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &impl Figure,
) -> Result<()> {
    root.fill(&WHITE).map_err(draw_err)?;
    figure.draw(root)?;
    root.present().map_err(draw_err)
}

/// Text style of the given pixel size in the embedded family.
pub(crate) fn text(size: f64) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(&BLACK)
}

/// Draws `title` centred in `area` (a strip at the top of the figure).
pub(crate) fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<()> {
    let (w, h) = area.dim_in_pixel();
    let style = text(TITLE_SIZE).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Center,
        plotters::style::text_anchor::VPos::Center,
    ));
    area.draw_text(title, &style, (w as i32 / 2, h as i32 / 2))
        .map_err(draw_err)
}

/// Height of the title strip at the top of every figure, pixels.
pub(crate) const TITLE_STRIP: u32 = 44;

/// The note of the sliding direction on maps and profiles along x (docs/architecture.md:
/// the frame is fixed to the slider, which moves in +x), longest form first.
const SLIDING_NOTES: [&str; 3] = [
    "slider moves +x \u{2192}",
    "slider +x \u{2192}",
    "+x \u{2192}",
];

/// Draws the sliding-direction note under a plotting area spanning the pixels `px`
/// (horizontally, absolute) whose bottom is at `bottom` (absolute): right-aligned with
/// the area, centred `below` pixels under it, in the longest form that keeps clear of a
/// centred x description `desc` (the same text as plotters draws there).
pub(crate) fn draw_sliding_note<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    px: std::ops::Range<i32>,
    bottom: i32,
    below: i32,
    desc: &str,
) -> Result<()> {
    let (desc_w, _) = area
        .estimate_text_size(desc, &text(LABEL_SIZE))
        .map_err(draw_err)?;
    let room = (px.end - px.start - desc_w as i32) / 2 - 12;
    let mut note = SLIDING_NOTES[SLIDING_NOTES.len() - 1];
    for n in SLIDING_NOTES {
        let (w, _) = area
            .estimate_text_size(n, &text(TICK_SIZE))
            .map_err(draw_err)?;
        if w as i32 <= room {
            note = n;
            break;
        }
    }
    let base = area.get_base_pixel();
    let style = text(TICK_SIZE).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Right,
        plotters::style::text_anchor::VPos::Center,
    ));
    area.draw_text(note, &style, (px.end - base.0, bottom - base.1 + below))
        .map_err(draw_err)
}

/// `text` with the ASCII spellings of the paper's symbols written as the symbols the
/// embedded font draws: whole words `mu`, `mu_linear`, `delta`, `tau1`, `sigma_x`, ...
/// become μ, μ(linear), δ, τ₁, σₓ (subscripts where Unicode has the glyph, else plain:
/// `sigma_y` is σy), and `E2`, `h1`, `p0`, `C0`, `nu1` take subscript digits; an
/// apostrophe right after a word (the dimensionless mark, `x'`) becomes the prime ′.
/// Other text is unchanged.
pub(crate) fn pretty(text: &str) -> String {
    fn symbol(word: &str) -> Option<&'static str> {
        Some(match word {
            "mu" => "\u{3bc}",
            "mu_linear" => "\u{3bc}(linear)",
            "delta" => "\u{3b4}",
            "nu1" => "\u{3bd}\u{2081}",
            "nu2" => "\u{3bd}\u{2082}",
            "tau1" => "\u{3c4}\u{2081}",
            "tau2" => "\u{3c4}\u{2082}",
            "tau3" => "\u{3c4}\u{2083}",
            "sigma_x" => "\u{3c3}\u{2093}",
            "sigma_y" => "\u{3c3}y",
            "sigma_z" => "\u{3c3}z",
            "tau_xy" => "\u{3c4}xy",
            "tau_xz" => "\u{3c4}xz",
            "tau_yz" => "\u{3c4}yz",
            "E1" => "E\u{2081}",
            "E2" => "E\u{2082}",
            "h1" => "h\u{2081}",
            "p0" => "p\u{2080}",
            "C0" => "C\u{2080}",
            _ => return None,
        })
    }
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        out.push_str(symbol(word).unwrap_or(word));
        word.clear();
    };
    for c in text.chars() {
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
        } else if c == '\'' && !word.is_empty() {
            // The dimensionless mark after a symbol (x', C'): the prime, which stays
            // visible also in rotated text, where an apostrophe is a speck.
            flush(&mut word, &mut out);
            out.push('\u{2032}');
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// Pixel sizes of the texts.
pub(crate) const TITLE_SIZE: f64 = 24.0;
/// Tick labels.
pub(crate) const TICK_SIZE: f64 = 17.0;
/// Axis descriptions and legend entries.
pub(crate) const LABEL_SIZE: f64 = 20.0;
