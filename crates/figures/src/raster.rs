//! PNG: the figure's SVG rendered by resvg with the fonts compiled into the crate (never
//! a system font: the font database holds only them), written with its resolution (the
//! pHYs chunk) so it prints at the size it was made for.

use super::text::{FAMILY, FONT_MONO, FONT_MONO_BOLD, FONT_OBLIQUE, FONT_REGULAR, MONO_FAMILY};
use crate::model::FigureError;
use resvg::{tiny_skia, usvg};
use std::sync::{Arc, OnceLock};

/// The fonts every figure is drawn with, and nothing else.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        for bytes in [FONT_REGULAR, FONT_OBLIQUE, FONT_MONO, FONT_MONO_BOLD] {
            db.load_font_source(usvg::fontdb::Source::Binary(Arc::new(bytes)));
        }
        for set in [
            usvg::fontdb::Database::set_sans_serif_family,
            usvg::fontdb::Database::set_serif_family,
            usvg::fontdb::Database::set_cursive_family,
            usvg::fontdb::Database::set_fantasy_family,
        ] {
            set(&mut db, FAMILY);
        }
        db.set_monospace_family(MONO_FAMILY);
        Arc::new(db)
    })
    .clone()
}

/// Largest side of a PNG, in pixels (12 inches at 600 dpi).
pub const MAX_PIXELS: u32 = 7200;

/// `svg` (a page of `size` inches) as PNG bytes at `dpi`.
pub fn png(svg: &str, size: (f64, f64), dpi: u32) -> Result<Vec<u8>, FigureError> {
    let options = usvg::Options {
        fontdb: fonts(),
        font_family: FAMILY.into(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options)
        .map_err(|e| FigureError(format!("figure: the drawing is not valid SVG: {e}")))?;
    let px = |inches: f64| ((inches * dpi as f64).round() as u32).clamp(1, MAX_PIXELS);
    let (w, h) = (px(size.0), px(size.1));
    let mut pixmap = tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| FigureError(format!("figure: cannot make a {w}×{h} image")))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let t = tree.size();
    let transform = tiny_skia::Transform::from_scale(w as f32 / t.width(), h as f32 / t.height());
    resvg::render(&tree, transform, &mut pixmap.as_mut());
    // Opaque (white page): the premultiplied RGBA is the RGB.
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let per_metre = (dpi as f64 / 0.0254).round() as u32;
    enc.set_pixel_dims(Some(png::PixelDimensions {
        xppu: per_metre,
        yppu: per_metre,
        unit: png::Unit::Meter,
    }));
    let encoded = enc
        .write_header()
        .and_then(|mut writer| {
            writer.write_image_data(&rgb)?;
            writer.finish()
        })
        .map_err(|e| FigureError(e.to_string()));
    encoded.map(|()| out)
}
