//! Whether a point on the map shows from the eye: the occlusion ray from the point to the eye,
//! in the frame's method and arithmetic. In exact arithmetic the answer is the geometry's: a
//! place is hidden exactly when the segment from its marker to the eye touches the terrain,
//! a ridge it grazes included.

use crate::arith::{run, Generic};
use crate::arith::{Arith, Scalar};
use crate::heightfield::Terrain;
use crate::traverse::{Method, Start, Tracer};

/// Sight lines over one terrain from one eye (in grid coordinates).
#[derive(Clone, Copy, Debug)]
pub struct Sight<'a> {
    /// The terrain that may hide points.
    pub terrain: &'a Terrain,
    /// The eye, in grid coordinates.
    pub eye: [f64; 3],
    /// The walk's method.
    pub method: Method,
    /// The arithmetic the occlusion rays run in.
    pub arith: Arith,
}

impl Sight<'_> {
    /// Whether the segment from `point` (grid coordinates) to the eye misses the terrain: the
    /// point's own place does not count, the eye's does.
    pub fn sees(&self, point: [f64; 3]) -> bool {
        let dir: [f64; 3] = std::array::from_fn(|k| self.eye[k] - point[k]);
        if dir == [0.0; 3] {
            return true;
        }
        let ray = SightRay {
            tracer: Tracer::new(self.terrain, self.method).within(1.0),
            from: point,
            dir,
        };
        let (ran, _) = run(self.arith, &ray);
        ran.output != Some(true)
    }

    /// The height of the ground at grid point `(x, y)` (on the map), on the triangle under it.
    pub fn ground(&self, [x, y]: [f64; 2]) -> f64 {
        let field = self.terrain.field();
        let last = |n: usize| n.saturating_sub(2);
        let i = (x.max(0.0).floor() as usize).min(last(field.width()));
        let j = (y.max(0.0).floor() as usize).min(last(field.height()));
        field.surface_z((i, j), (x - i as f64, y - j as f64))
    }
}

/// One occlusion ray from a point, in whichever arithmetic [`run`] picks.
struct SightRay<'a> {
    tracer: Tracer<'a>,
    from: [f64; 3],
    dir: [f64; 3],
}

impl Generic for SightRay<'_> {
    type Output = Option<bool>;
    fn run<S: Scalar>(&self) -> Option<bool> {
        let origin = self.from.map(S::from_f64);
        let occlusion = self.tracer.occluded(&Start::Point(&origin), self.dir, true);
        occlusion.occluded
    }
}
