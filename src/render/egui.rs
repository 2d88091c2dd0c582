//! The egui backend (feature `explore`): a scene's [`Tiles`] as epaint shapes.
//!
//! The background is one filled rectangle and every tile a textured rectangle mesh, drawn in
//! the scene's order. The tiles hold the PNG renderer's pixels (glyph outlines of the embedded
//! Ubuntu Light — the face egui's default fonts ship too — the point-stamp blitter and the line
//! rasterizer for batches), so the window shows the same pixels as `NAME.png`, at the window's
//! pixel density. Textures are uploaded when a tile's version changes, so relighting a
//! selection only uploads the tiles that were redrawn.

use eframe::egui::{self, Color32, Pos2, Shape, TextureHandle, TextureOptions};
use eframe::epaint::ColorImage;

use super::tiles::Tiles;
use crate::scene::Color;

/// The textures of one [`Tiles`], kept between frames.
#[derive(Default)]
pub struct TextureCache {
    /// Which [`Tiles`] the textures are of.
    tiles_id: u64,
    /// Per tile: the version uploaded and its texture.
    textures: Vec<Option<(u64, TextureHandle)>>,
}

impl std::fmt::Debug for TextureCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TextureCache({} textures)", self.textures.iter().flatten().count())
    }
}

impl TextureCache {
    /// Forget every texture (the tiles were replaced).
    pub fn clear(&mut self) {
        self.textures.clear();
    }
}

/// An egui colour from a scene colour (straight alpha).
pub fn color32(c: Color) -> Color32 {
    Color32::from_rgba_unmultiplied(c.r, c.g, c.b, c.a)
}

/// The shapes that paint `tiles` with the canvas' top-left corner at `origin` (points; one
/// canvas unit is one point), uploading changed tiles to `cache` first.
pub fn shapes(ctx: &egui::Context, tiles: &Tiles, origin: Pos2, cache: &mut TextureCache) -> Vec<Shape> {
    let to_screen = |x: f64, y: f64| Pos2::new(origin.x + x as f32, origin.y + y as f32);
    let mut out = Vec::with_capacity(tiles.tiles.len() + 1);
    let canvas = egui::Rect::from_min_max(to_screen(0.0, 0.0), to_screen(tiles.width, tiles.height));
    out.push(Shape::rect_filled(canvas, 0.0, color32(tiles.background)));
    if cache.tiles_id != tiles.id {
        cache.textures.clear();
        cache.tiles_id = tiles.id;
    }
    cache.textures.resize_with(tiles.tiles.len(), || None);
    for (i, tile) in tiles.tiles.iter().enumerate() {
        if tile.width == 0 || tile.height == 0 {
            continue;
        }
        let size = [tile.width as usize, tile.height as usize];
        let Some(slot) = cache.textures.get_mut(i) else { continue };
        let fresh = || ColorImage::from_rgba_premultiplied(size, &tile.rgba);
        match slot {
            Some((version, handle)) if *version == tile.version => {
                let _ = handle;
            }
            Some((version, handle)) => {
                handle.set(fresh(), TextureOptions::NEAREST);
                *version = tile.version;
            }
            None => {
                let handle = ctx.load_texture(format!("dataink-tile-{i}"), fresh(), TextureOptions::NEAREST);
                *slot = Some((tile.version, handle));
            }
        }
        let Some((_, handle)) = slot.as_ref() else { continue };
        let r = tile.rect;
        let rect = egui::Rect::from_min_max(to_screen(r.x, r.y), to_screen(r.right(), r.bottom()));
        let uv = egui::Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        out.push(Shape::image(handle.id(), rect, uv, Color32::WHITE));
    }
    out
}
