//! Files dropped onto the window: gathered while a drop delivers them one by one, then loaded
//! as one request: a height map or scene, tiles joined into one map, or an overlay. A single
//! picture (a JPEG, an RGB TIFF) dropped as a height map is laid over the map instead, as it
//! holds no heights.

use super::overlay_ui::overlay_request;
use super::state::{DropLoads, LoadRequest, Model, OverlayChange, Source};
use crate::heightfield;
use std::path::PathBuf;

/// The request the files dropped since the last call make, if any were dropped.
pub fn take(model: &mut Model) -> Option<LoadRequest> {
    let mut paths = std::mem::take(&mut model.dropped);
    let picture = match paths.as_slice() {
        [path] => heightfield::picture_kind(path),
        _ => None,
    };
    match (model.widgets.overlay.drop_loads, picture) {
        (DropLoads::HeightMap, Some(what)) => {
            let path = paths.pop()?;
            model.widgets.overlay.dropped_picture = Some(what);
            let opacity = model.widgets.overlay.opacity;
            Some(overlay_request(
                &model.shown,
                OverlayChange::Lay { path, opacity },
            ))
        }
        (DropLoads::HeightMap, None) => Some(LoadRequest {
            source: Source::of_paths(paths)?,
            z_scale: None,
            reframe: true,
            from_memory: None,
            decoding: model.widgets.decoding,
            overlay: None,
        }),
        (DropLoads::Overlay, _) => {
            // One image at a time: the last one dropped.
            let path: PathBuf = paths.pop()?;
            let opacity = model.widgets.overlay.opacity;
            Some(overlay_request(
                &model.shown,
                OverlayChange::Lay { path, opacity },
            ))
        }
    }
}
