//! Files dropped onto the window: gathered while a drop delivers them one by one, then loaded
//! as one request: a height map or scene, tiles joined into one map, or an overlay. A single
//! picture (a JPEG, an RGB TIFF) dropped as a height map is laid over the map instead, as it
//! holds no heights.

use super::loader::{LoadRequest, OverlayChange, Source};
use super::model::Model;
use super::overlay_ui::overlay_request;
use crate::heightfield;
use std::path::PathBuf;

/// What files dropped onto the window load.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DropLoads {
    /// A new height map (or scene), or tiles joined into one.
    #[default]
    HeightMap,
    /// An image draped over the map on screen.
    Overlay,
}

/// The request the files dropped since the last call make, if any were dropped.
pub fn take(model: &mut Model) -> Option<LoadRequest> {
    let mut paths = std::mem::take(&mut model.dropped);
    let picture = match paths.as_slice() {
        [path] => heightfield::picture_kind(path),
        _ => None,
    };
    match (model.overlay.drop_loads, picture) {
        (DropLoads::HeightMap, Some(what)) => {
            let path = paths.pop()?;
            model.overlay.dropped_picture = Some(what);
            let opacity = model.overlay.opacity;
            Some(overlay_request(model, OverlayChange::Lay { path, opacity }))
        }
        (DropLoads::HeightMap, None) => Some(LoadRequest {
            source: Source::of_paths(paths)?,
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: model.decoding,
            overlay: None,
        }),
        (DropLoads::Overlay, _) => {
            // One image at a time: the last one dropped.
            let path: PathBuf = paths.pop()?;
            let opacity = model.overlay.opacity;
            Some(overlay_request(model, OverlayChange::Lay { path, opacity }))
        }
    }
}
