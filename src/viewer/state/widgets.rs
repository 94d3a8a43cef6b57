//! What the panels' fields and toggles hold between frames.

use super::loads::{Decoding, Source};
use crate::heightfield::Heightfield;
use crate::render::{level_z, Contours};
use std::collections::BTreeMap;

/// Contour lines as the panel edits them.
#[derive(Clone, Debug, PartialEq)]
pub struct ContourControls {
    pub on: bool,
    /// Height between lines in the map's height unit; 0 until one is typed or picked.
    pub interval: f64,
    /// Every this many lines is a wider index line (0: none).
    pub index_every: u32,
    /// The interval field as typed (taken when editing ends).
    pub text: String,
}

impl Default for ContourControls {
    fn default() -> Self {
        ContourControls {
            on: false,
            interval: 0.0,
            index_every: 5,
            text: String::new(),
        }
    }
}

impl ContourControls {
    /// The lines to draw on `field` (grid heights through [`level_z`], as a scene's are), if on.
    pub fn lines(&self, field: &Heightfield) -> Option<Contours> {
        self.on
            .then(|| Contours::new(level_z(field, self.interval), self.index_every))
            .flatten()
    }

    /// Sets the interval, and the field that shows it.
    pub fn set_interval(&mut self, interval: f64) {
        self.interval = interval;
        self.text = interval.to_string();
    }

    /// A scene's `[overlay] contours` and `index_every`: lines as it gives them, or none.
    pub fn adopt(&mut self, scene: Option<(f64, u32)>) {
        self.on = scene.is_some();
        if let Some((interval, index_every)) = scene {
            self.set_interval(interval);
            self.index_every = index_every;
        }
    }

    /// The `contours` and `index_every` keys of a scene's `[overlay]`, if lines are drawn.
    pub fn scene_keys(&self, field: &Heightfield) -> Option<String> {
        self.lines(field).map(|_| {
            format!(
                "contours = {:?}\nindex_every = {}\n",
                self.interval, self.index_every
            )
        })
    }
}

/// The overlay controls' state.
#[derive(Clone, Debug, PartialEq)]
pub struct OverlayControls {
    /// The overlay path field.
    pub path_text: String,
    /// The opacity an overlay is laid with.
    pub opacity: f64,
    /// What a dropped file loads.
    pub drop_loads: DropLoads,
    /// What kind of picture was dropped as a height map and is being laid as an overlay.
    pub dropped_picture: Option<String>,
}

impl Default for OverlayControls {
    fn default() -> Self {
        OverlayControls {
            path_text: String::new(),
            opacity: 1.0,
            drop_loads: DropLoads::default(),
            dropped_picture: None,
        }
    }
}

/// What files dropped onto the window load.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DropLoads {
    /// A new height map (or scene), or tiles joined into one.
    #[default]
    HeightMap,
    /// An image draped over the map on screen.
    Overlay,
}

/// The panels' fields and toggles.
pub struct Widgets {
    /// The z scale field of the heightmap panel (applied when editing ends).
    pub z_scale: f64,
    /// The path field of the heightmap panel.
    pub path_text: String,
    /// The terrain the path field was last filled in for (it shows what is loaded).
    pub path_source: Option<Source>,
    /// How images opened or dropped from now on are decoded.
    pub decoding: Decoding,
    /// The overlay path, opacity and what a drop loads.
    pub overlay: OverlayControls,
    /// Contour lines on the map.
    pub contours: ContourControls,
    pub panels_visible: bool,
    /// The panel was hidden because the window became too narrow for it.
    pub panel_auto_hidden: bool,
    /// Show the ray of the pixel under a resting pointer.
    pub show_probe: bool,
    pub help_open: bool,
    /// Where named widgets were drawn last frame, in points (for scripted tests).
    pub rects: BTreeMap<&'static str, egui::Rect>,
}
