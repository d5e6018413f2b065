//! Back-face culling, a stage any method can use.
//!
//! Two tests, as the textbooks give them (Foley, van Dam, Feiner & Hughes §15.2.4) and as
//! hardware does:
//!
//! - **Normal versus view**: with `V` the viewing direction (from the eye towards
//!   the face) and `N` the face's outward normal, the face is a back face when `V·N > 0`, and
//!   edge-on (never visible) when `V·N = 0`. Under an orthographic view along −z this is the
//!   sign of the normal's z component (the classic "back face if C < 0", C the plane equation's z coefficient, with the viewer on +z).
//!   Model mode applies it in view space before clipping, so culled faces cost no projection.
//! - **Winding on snapped coordinates** ([`crate::raster::setup`]): after snapping, a polygon
//!   that is clockwise on the display is a back face, and one with zero area is dropped as
//!   back-facing whatever the cull mode.

use crate::math::Vec3;
use crate::number::Scalar;

/// The normal test: `true` when `V·N >= 0`, i.e. the face points away from the viewer or is
/// seen edge-on. `view` points from the eye towards the face.
///
/// ```
/// use zrow::{backface::is_back_face, math::Vec3};
/// // The unit cube seen from (5, -1, 5), looking at the origin.
/// let v = Vec3::<f32>::new(-5.0, 1.0, -5.0);
/// let n = |x, y, z| Vec3::new(x, y, z);
/// assert!(!is_back_face(n(1.0, 0.0, 0.0), v)); // +x visible
/// assert!(is_back_face(n(0.0, 1.0, 0.0), v)); // +y hidden
/// ```
pub fn is_back_face<N: Scalar>(normal: Vec3<N>, view: Vec3<N>) -> bool {
    normal.dot(view) >= N::ZERO
}
