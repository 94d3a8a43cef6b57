//! Moving about the map: the framed view that follows the view's shape, R and F, the keys that
//! walk, turn and zoom, and the rule applied after every move (see [`ground::keep_above`]).

use super::ground;
use super::orbit::Orbit;
use super::state::{Action, Framed, Home, Model};
use crate::render::framing::{DEFAULT_FOV_Y_DEG, DEFAULT_PITCH_DEG, DEFAULT_YAW_DEG};
use crate::Terrain;
use std::sync::Arc;

/// Share of the distance one arrow key press walks the target.
const WALK_STEP: f64 = 0.1;
/// Degrees one Q or E press turns.
const TURN_STEP_DEG: f64 = 10.0;
/// Wheel steps one + or - press zooms.
const ZOOM_KEY_STEPS: f64 = 2.0;
/// Framing from the current direction looks down at least this much, so the map is seen
/// from above rather than edge on.
const FRAME_MIN_PITCH_DEG: f64 = 20.0;

/// The camera over the terrain on screen, and what frames it: what moving about edits.
pub struct Placing<'a> {
    pub orbit: &'a mut Orbit,
    /// Set while the camera shows the whole map as framed, and not moved since.
    pub framed: &'a mut Option<Framed>,
    /// The 3D view's width over its height.
    pub view_aspect: &'a mut f64,
    /// Where R returns to.
    pub home: Home,
    pub terrain: &'a Arc<Terrain>,
}

impl<'a> Placing<'a> {
    /// The model's camera and what frames it.
    pub fn of(model: &'a mut Model) -> Placing<'a> {
        Placing {
            orbit: &mut model.orbit,
            framed: &mut model.framed,
            view_aspect: &mut model.view_aspect,
            home: model.home,
            terrain: &model.shown.terrain,
        }
    }

    /// Frames the whole map from the given angles for the view's current shape.
    fn frame_map(&mut self, yaw_deg: f64, pitch_deg: f64) {
        let aspect = *self.view_aspect;
        let mut orbit = Orbit::fit(
            self.terrain,
            yaw_deg,
            pitch_deg,
            self.orbit.fov_y_deg,
            aspect,
        );
        ground::keep_above(&mut orbit, self.terrain);
        *self.orbit = orbit;
        *self.framed = Some(Framed {
            yaw_deg,
            pitch_deg,
            aspect,
            orbit,
            terrain: terrain_id(self.terrain),
        });
    }

    /// Run once per frame after the camera input, with the view's shape: a framed view that
    /// was not moved since follows the shape, and every move ends within the ground rule.
    pub fn settle(&mut self, aspect: f64) {
        if aspect.is_finite() && aspect > 0.0 {
            *self.view_aspect = aspect;
        }
        match *self.framed {
            Some(framed) if framed.orbit != *self.orbit => *self.framed = None,
            Some(framed)
                if framed.aspect != *self.view_aspect
                    || framed.terrain != terrain_id(self.terrain) =>
            {
                self.frame_map(framed.yaw_deg, framed.pitch_deg);
            }
            _ => {}
        }
        // A scene's camera is shown as its file has it, wherever that is, until it is moved.
        if self.home != Home::Scene(*self.orbit) {
            ground::keep_above(self.orbit, self.terrain);
        }
    }
}

/// The identity of a terrain.
fn terrain_id(terrain: &Arc<Terrain>) -> usize {
    Arc::as_ptr(terrain) as usize
}

/// Frames the whole map from where the camera looks now (F, and the panel's button).
pub fn frame_from_here(model: &mut Model) {
    let (yaw, pitch) = (model.orbit.yaw_deg, model.orbit.pitch_deg);
    Placing::of(model).frame_map(yaw, pitch.max(FRAME_MIN_PITCH_DEG));
}

/// Returns to the home view (R): a scene's camera, or the whole map from the default angles.
pub fn reset(model: &mut Model) {
    match model.home {
        Home::Scene(orbit) => {
            model.orbit = orbit;
            model.framed = None;
        }
        Home::WholeMap => {
            model.orbit.fov_y_deg = DEFAULT_FOV_Y_DEG;
            Placing::of(model).frame_map(DEFAULT_YAW_DEG, DEFAULT_PITCH_DEG);
        }
    }
}

/// Arrows walk `orbit`'s target over `terrain`, Q and E turn, + and - zoom, PageUp and
/// PageDown tilt; F (framing the whole map) and R (returning home) are asked for.
pub fn keys_ui(ui: &egui::Ui, orbit: &mut Orbit, terrain: &Terrain) -> Vec<Action> {
    use egui::Key;
    let mut actions = Vec::new();
    let pressed = |key| ui.input(|i| i.key_pressed(key));
    let walks = [
        (Key::ArrowUp, (1.0, 0.0)),
        (Key::ArrowDown, (-1.0, 0.0)),
        (Key::ArrowLeft, (0.0, -1.0)),
        (Key::ArrowRight, (0.0, 1.0)),
    ];
    for (key, (ahead, aside)) in walks {
        if pressed(key) {
            orbit.walk(WALK_STEP * ahead, WALK_STEP * aside);
            // The target walks on the ground, not through the air above a valley.
            let [x, y, _] = orbit.target;
            orbit.target[2] = ground::surface_z(terrain, x, y);
        }
    }
    if pressed(Key::Q) {
        orbit.turn(TURN_STEP_DEG);
    }
    if pressed(Key::E) {
        orbit.turn(-TURN_STEP_DEG);
    }
    if pressed(Key::Plus) || pressed(Key::Equals) {
        orbit.zoom(ZOOM_KEY_STEPS);
    }
    if pressed(Key::Minus) {
        orbit.zoom(-ZOOM_KEY_STEPS);
    }
    if pressed(Key::PageUp) {
        orbit.tilt(TURN_STEP_DEG);
    }
    if pressed(Key::PageDown) {
        orbit.tilt(-TURN_STEP_DEG);
    }
    if pressed(Key::F) {
        actions.push(Action::FrameMap);
    }
    if pressed(Key::R) {
        actions.push(Action::ResetView);
    }
    actions
}

/// The camera section's extra: framing the whole map.
pub fn tools_ui(ui: &mut egui::Ui, actions: &mut Vec<Action>) {
    if ui
        .button("Frame map (F)")
        .on_hover_text("fit the whole map in the view, from the current direction")
        .clicked()
    {
        actions.push(Action::FrameMap);
    }
}
