//! The scene model: meshes as borrowed slices (so they can live in flash), objects with a model
//! transform, a camera, one directional light; and screen-space scenes.

use crate::error::Error;
use crate::math::{Affine, Vec3};
use crate::number::{DepthPlane, Scalar};
use crate::raster::{Config, RasterPolygon, RasterVertex};
use embedded_graphics_core::pixelcolor::Rgb565;

mod sealed {
    /// Keeps [`super::MeshIndex`] implemented for `u8`, `u16` and `u32` only.
    pub trait Sealed {}
    impl Sealed for u8 {}
    impl Sealed for u16 {}
    impl Sealed for u32 {}
}

/// The integer type of a mesh's vertex indices: `u16` (the default, up to 65,536 vertices),
/// `u8` (up to 256 vertices, half the flash per index) or `u32` (any mesh: models of hundreds
/// of thousands of vertices on a host). A model converter picks the narrowest one that fits
/// the mesh. Sealed: only `u8`, `u16` and `u32` implement it.
pub trait MeshIndex: Copy + core::fmt::Debug + PartialEq + 'static + sealed::Sealed {
    /// The largest vertex count the type can address (256 for `u8`, 65,536 for `u16`,
    /// 2³² for `u32`).
    const MAX: usize;
    /// The index as a `usize`, for looking the vertex up.
    fn index(self) -> usize;
}

impl MeshIndex for u8 {
    const MAX: usize = 1 << 8;
    #[inline]
    fn index(self) -> usize {
        self as usize
    }
}

impl MeshIndex for u16 {
    const MAX: usize = 1 << 16;
    #[inline]
    fn index(self) -> usize {
        self as usize
    }
}

impl MeshIndex for u32 {
    // 2³² does not fit a 32-bit `usize`: the largest count that does.
    const MAX: usize = (u32::MAX as usize).saturating_add(1);
    #[inline]
    fn index(self) -> usize {
        self as usize
    }
}

/// A face: a convex planar polygon given by vertex indices (of type `I`, see [`MeshIndex`]),
/// and its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face<'a, I = u16> {
    /// Indices into the mesh's vertices, in order. Counter-clockwise seen from outside for
    /// meshes that are culled.
    pub indices: &'a [I],
    /// Colour (screen-space mode draws it as is; model mode shades it).
    pub color: Rgb565,
    /// Opacity, 255 = opaque (the default). Methods that resolve one visible surface per
    /// pixel treat every face as opaque; [`crate::abuffer`] blends translucent faces over the
    /// opaque surface behind them.
    pub alpha: u8,
}

impl<'a, I: MeshIndex> Face<'a, I> {
    /// An opaque face with indices of any [`MeshIndex`] type: `u8` (a converted model of up to
    /// 256 vertices), `u16` or `u32` (host-sized meshes).
    ///
    /// ```
    /// use zrow::{Face, Rgb565};
    /// let small: Face<'_, u8> = Face::opaque(&[0u8, 1, 2], Rgb565::new(31, 0, 0));
    /// assert_eq!((small.indices, small.alpha), (&[0u8, 1, 2][..], 255));
    /// ```
    pub const fn opaque(indices: &'a [I], color: Rgb565) -> Self {
        Face {
            indices,
            color,
            alpha: 255,
        }
    }

    /// A face with opacity `alpha` (0 = invisible, 255 = opaque), indices of any type.
    pub const fn translucent_of(indices: &'a [I], color: Rgb565, alpha: u8) -> Self {
        Face {
            indices,
            color,
            alpha,
        }
    }
}

impl<'a> Face<'a, u16> {
    /// An opaque face with `u16` indices (so integer literals need no suffix; any index type:
    /// [`Face::opaque`]).
    pub const fn new(indices: &'a [u16], color: Rgb565) -> Self {
        Face {
            indices,
            color,
            alpha: 255,
        }
    }
    /// A face with opacity `alpha` (0 = invisible, 255 = opaque), `u16` indices (any index
    /// type: [`Face::translucent_of`]).
    pub const fn translucent(indices: &'a [u16], color: Rgb565, alpha: u8) -> Self {
        Face {
            indices,
            color,
            alpha,
        }
    }
}

/// A mesh's faces: a list of [`Face`]s or, in less than half the flash, opaque triangles.
///
/// A [`Face`] is a slice (8 bytes on a 32-bit MCU) plus its colour and opacity: 12 bytes
/// besides its indices. Triangles need only their indices and colours: the 1,000-triangle
/// torus is 6,000 bytes of `u16` indices and 2,000 of colours as [`Faces::Triangles`]
/// instead of 18,000 as a list of faces (and 6,000 with one colour for all). Either kind is
/// read through [`Faces::get`] and [`Faces::iter`], which hand out each face as a [`Face`]
/// (by value, borrowing the same indices).
///
/// ```
/// use zrow::{Face, Faces, Mesh, Rgb565, Vec3};
/// let v = [Vec3::new(0.0f32, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
/// let green = [Rgb565::new(0, 63, 0)];
/// let tris = Mesh::triangles(&v, &[[0u16, 1, 2]], &green);
/// let list = [Face::new(&[0, 1, 2], green[0])];
/// assert_eq!(tris.faces.len(), 1);
/// assert_eq!(tris.faces.get(0), Mesh::new(&v, &list).faces.get(0));
/// assert!(matches!(tris.faces, Faces::Triangles { .. }));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Faces<'a, I = u16> {
    /// Faces of any number of corners, each with its colour and opacity.
    List(&'a [Face<'a, I>]),
    /// Opaque triangles.
    Triangles {
        /// Each triangle's corners (counter-clockwise seen from outside for meshes that are
        /// culled).
        indices: &'a [[I; 3]],
        /// One colour per triangle, or one for all of them; any other length is
        /// [`Error::Colors`].
        colors: &'a [Rgb565],
    },
}

impl<'a, I> Faces<'a, I> {
    /// How many faces.
    pub const fn len(&self) -> usize {
        match self {
            Faces::List(l) => l.len(),
            Faces::Triangles { indices, .. } => indices.len(),
        }
    }

    /// Whether there is none.
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Face `k`, or `None` past the end.
    #[inline]
    pub fn get(&self, k: usize) -> Option<Face<'a, I>>
    where
        I: Copy,
    {
        match *self {
            Faces::List(l) => l.get(k).copied(),
            Faces::Triangles { indices, colors } => Some(Face {
                indices: indices.get(k)?,
                color: *match colors {
                    [one] => one,
                    _ => colors.get(k)?,
                },
                alpha: 255,
            }),
        }
    }

    /// The faces in order.
    #[inline]
    pub fn iter(&self) -> FacesIter<'a, I> {
        match *self {
            Faces::List(l) => FacesIter::List(l.iter()),
            Faces::Triangles { indices, colors } => FacesIter::Triangles(indices.iter(), colors),
        }
    }
}

impl<'a, I> From<&'a [Face<'a, I>]> for Faces<'a, I> {
    fn from(list: &'a [Face<'a, I>]) -> Self {
        Faces::List(list)
    }
}

impl<'a, I, const K: usize> From<&'a [Face<'a, I>; K]> for Faces<'a, I> {
    fn from(list: &'a [Face<'a, I>; K]) -> Self {
        Faces::List(list)
    }
}

impl<'a, I: Copy> IntoIterator for Faces<'a, I> {
    type Item = Face<'a, I>;
    type IntoIter = FacesIter<'a, I>;
    fn into_iter(self) -> FacesIter<'a, I> {
        self.iter()
    }
}

/// The faces of a [`Faces`] in order ([`Faces::iter`]).
#[derive(Clone, Debug)]
pub enum FacesIter<'a, I> {
    #[doc(hidden)]
    List(core::slice::Iter<'a, Face<'a, I>>),
    #[doc(hidden)]
    Triangles(core::slice::Iter<'a, [I; 3]>, &'a [Rgb565]),
}

impl<'a, I: Copy> Iterator for FacesIter<'a, I> {
    type Item = Face<'a, I>;
    #[inline]
    fn next(&mut self) -> Option<Face<'a, I>> {
        match self {
            FacesIter::List(l) => l.next().copied(),
            FacesIter::Triangles(t, colors) => {
                let c: &'a [Rgb565] = colors;
                let color = match c {
                    [one] => *one,
                    [first, rest @ ..] => {
                        *colors = rest;
                        *first
                    }
                    [] => return None,
                };
                Some(Face {
                    indices: t.next()?,
                    color,
                    alpha: 255,
                })
            }
        }
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        match self {
            FacesIter::List(l) => l.size_hint(),
            FacesIter::Triangles(t, _) => t.size_hint(),
        }
    }
}

impl<I: Copy> ExactSizeIterator for FacesIter<'_, I> {}

/// A mesh's 3-vectors — its vertex positions ([`Mesh::vertices`]) and its face normals
/// ([`Mesh::normals`]): in the number format, or compact (16-bit integers and one
/// power-of-two scale, half the flash of a 32-bit format; a unit normal at 2^-14 is within
/// 2^-15 of its direction).
///
/// ```
/// use zrow::{Vectors, Q16_16, Scalar};
/// // (0.5, -1.25, 2.0) at 2^-14: 6 bytes a vertex.
/// static RAW: [[i16; 3]; 1] = [[8192, -20480, 32767]];
/// let p: Vectors<'_, Q16_16> = Vectors::Compact { raw: &RAW, shift: 14 };
/// let v = p.get(0).unwrap();
/// assert_eq!((v.x.to_f32(), v.y.to_f32()), (0.5, -1.25));
/// assert_eq!(v.z.to_bits(), 32767 << 2); // exact: 2^-14 is a multiple of 2^-16
/// assert_eq!(p.len(), 1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Vectors<'a, N> {
    /// In the number format: 12 bytes a vector in every format.
    Format(&'a [Vec3<N>]),
    /// Each coordinate is `raw · 2^-shift` (6 bytes a vector): exact in f32, in Q16.16 for
    /// `shift ≤ 16` and in Q24.8 for `shift ≤ 8`, rounded to nearest otherwise. With shift
    /// 14 a model spans ±2 units in steps of 2^-14.
    Compact {
        /// The coordinates, scaled by 2^shift.
        raw: &'a [[i16; 3]],
        /// The power of two they are scaled by.
        shift: u8,
    },
}

impl<N> Vectors<'_, N> {
    /// How many vectors.
    #[inline]
    pub const fn len(&self) -> usize {
        match self {
            Vectors::Format(v) => v.len(),
            Vectors::Compact { raw, .. } => raw.len(),
        }
    }
    /// Whether there are none.
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<N: Scalar> Vectors<'_, N> {
    /// Vector `i` in the number format, or `None` past the end.
    #[inline]
    pub fn get(&self, i: usize) -> Option<Vec3<N>> {
        match self {
            Vectors::Format(v) => v.get(i).copied(),
            Vectors::Compact { raw, shift } => raw.get(i).map(|r| compact(r, *shift)),
        }
    }
    /// Every vector in order, in the number format.
    pub fn iter(&self) -> VectorsIter<'_, N> {
        match self {
            Vectors::Format(v) => VectorsIter::Format(v.iter()),
            Vectors::Compact { raw, shift } => VectorsIter::Compact(raw.iter(), *shift),
        }
    }
}

/// The iterator of [`Vectors::iter`].
#[derive(Clone, Debug)]
pub enum VectorsIter<'a, N> {
    /// Over positions in the number format.
    Format(core::slice::Iter<'a, Vec3<N>>),
    /// Over compact positions and their shift.
    Compact(core::slice::Iter<'a, [i16; 3]>, u8),
}

impl<N: Scalar> Iterator for VectorsIter<'_, N> {
    type Item = Vec3<N>;
    #[inline]
    fn next(&mut self) -> Option<Vec3<N>> {
        match self {
            VectorsIter::Format(v) => v.next().copied(),
            VectorsIter::Compact(raw, shift) => raw.next().map(|r| compact(r, *shift)),
        }
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        match self {
            VectorsIter::Format(v) => v.size_hint(),
            VectorsIter::Compact(raw, _) => raw.size_hint(),
        }
    }
}

impl<N: Scalar> ExactSizeIterator for VectorsIter<'_, N> {}

/// A compact position in the number format ([`Scalar::from_compact`]: always fits).
#[inline]
fn compact<N: Scalar>(r: &[i16; 3], shift: u8) -> Vec3<N> {
    let c = |v: i16| N::from_compact(v, shift as u32);
    Vec3::new(c(r[0]), c(r[1]), c(r[2]))
}

/// A mesh: vertices, faces and optionally one normal per face, all borrowed (so a converted
/// model can live in flash).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mesh<'a, N, I = u16> {
    /// Vertex positions.
    pub vertices: Vectors<'a, N>,
    /// Faces: a list of [`Face`]s, or triangles of one colour ([`Faces`]).
    pub faces: Faces<'a, I>,
    /// Precomputed face normals, or empty. Empty: model mode computes each face's normal per
    /// frame from its first three (transformed) vertices. Otherwise exactly one model-space
    /// outward normal per face, of unit length (any positive length works; a zero normal
    /// marks a degenerate face, which is skipped); model mode transforms it to view space
    /// and uses it for back-face culling and lighting instead of the cross product.
    /// Screen-space mode ignores it. Any other length is [`Error::Normals`].
    pub normals: Vectors<'a, N>,
    /// Per-vertex model-space unit normals for smooth shading
    /// ([`Shading::Gouraud`](crate::shading::Shading::Gouraud)), or empty (the faces are then
    /// drawn flat under every shading). Otherwise exactly one per vertex (a vertex on a crease
    /// is split into one per side, as the model converter's `--smooth` does); any other
    /// length is [`Error::VertexNormals`]. Flat shading ignores them.
    pub vertex_normals: Vectors<'a, N>,
}

impl<'a, N, I> Mesh<'a, N, I> {
    /// A mesh whose normals model mode computes per frame.
    pub const fn new(vertices: &'a [Vec3<N>], faces: &'a [Face<'a, I>]) -> Self {
        Mesh {
            vertices: Vectors::Format(vertices),
            faces: Faces::List(faces),
            normals: Vectors::Format(&[]),
            vertex_normals: Vectors::Format(&[]),
        }
    }
    /// A mesh of opaque triangles ([`Faces::Triangles`]: 6 bytes a triangle with `u16`
    /// indices, and 2 for its colour unless one colour is given for all, instead of 18 as a
    /// list of [`Face`]s), whose normals model mode computes per frame.
    pub const fn triangles(
        vertices: &'a [Vec3<N>],
        indices: &'a [[I; 3]],
        colors: &'a [Rgb565],
    ) -> Self {
        Mesh {
            vertices: Vectors::Format(vertices),
            faces: Faces::Triangles { indices, colors },
            normals: Vectors::Format(&[]),
            vertex_normals: Vectors::Format(&[]),
        }
    }
    /// [`Mesh::triangles`] with one precomputed model-space unit normal per triangle (see
    /// [`Mesh::normals`]): what the model converter emits for a model of triangles.
    pub const fn triangles_with_normals(
        vertices: &'a [Vec3<N>],
        indices: &'a [[I; 3]],
        colors: &'a [Rgb565],
        normals: &'a [Vec3<N>],
    ) -> Self {
        Mesh {
            vertices: Vectors::Format(vertices),
            faces: Faces::Triangles { indices, colors },
            normals: Vectors::Format(normals),
            vertex_normals: Vectors::Format(&[]),
        }
    }
    /// A mesh with one precomputed model-space unit normal per face (see [`Mesh::normals`]).
    pub const fn with_normals(
        vertices: &'a [Vec3<N>],
        faces: &'a [Face<'a, I>],
        normals: &'a [Vec3<N>],
    ) -> Self {
        Mesh {
            vertices: Vectors::Format(vertices),
            faces: Faces::List(faces),
            normals: Vectors::Format(normals),
            vertex_normals: Vectors::Format(&[]),
        }
    }
    /// The same mesh with its positions from `vertices` (compact ones, say).
    pub const fn with_positions(self, vertices: Vectors<'a, N>) -> Self {
        Mesh { vertices, ..self }
    }
    /// The same mesh with its face normals from `normals` (compact ones, say; see
    /// [`Mesh::normals`]).
    pub const fn with_normal_vectors(self, normals: Vectors<'a, N>) -> Self {
        Mesh { normals, ..self }
    }
    /// The same mesh with one model-space unit normal per vertex (see
    /// [`Mesh::vertex_normals`]), for smooth shading.
    pub const fn with_vertex_normals(self, vertex_normals: Vectors<'a, N>) -> Self {
        Mesh {
            vertex_normals,
            ..self
        }
    }
    /// Checks that `normals` is empty or has one entry per face, `vertex_normals` empty or
    /// one per vertex, and that triangles have one colour each or one for all.
    pub(crate) fn check(&self) -> Result<(), Error> {
        let (faces, normals) = (self.faces.len(), self.normals.len());
        if normals != 0 && normals != faces {
            return Err(Error::Normals {
                faces: faces as u32,
                normals: normals as u32,
            });
        }
        let (vertices, normals) = (self.vertices.len(), self.vertex_normals.len());
        if normals != 0 && normals != vertices {
            return Err(Error::VertexNormals {
                vertices: vertices as u32,
                normals: normals as u32,
            });
        }
        match self.faces {
            Faces::Triangles { colors, .. } if colors.len() != 1 && colors.len() != faces => {
                Err(Error::Colors {
                    faces: faces as u32,
                    colors: colors.len() as u32,
                })
            }
            _ => Ok(()),
        }
    }
}

/// A mesh placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Object<'a, N, I = u16> {
    /// The mesh.
    pub mesh: &'a Mesh<'a, N, I>,
    /// Model → world transform.
    pub transform: Affine<N>,
}

/// How the camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection<N> {
    /// Perspective: `focal` = cot(vertical field of view / 2).
    Perspective {
        /// cot(fov_y / 2).
        focal: N,
        /// Near plane distance (> 0): only geometry beyond it is drawn.
        near: N,
        /// Far plane distance.
        far: N,
    },
    /// Orthographic: `half_height` world units from the centre to the top of the screen.
    Orthographic {
        /// Half the visible height in world units.
        half_height: N,
        /// Near plane distance.
        near: N,
        /// Far plane distance.
        far: N,
    },
}

/// A camera: a world → view transform (looking down −z, y up) and a projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<N> {
    /// World → view.
    pub view: Affine<N>,
    /// Projection.
    pub projection: Projection<N>,
}

impl<N: Scalar> Camera<N> {
    /// A look-at camera, computed in `f32` and converted. `None` if `eye == target`, `up` is
    /// parallel to the view direction, or a value does not fit the format.
    pub fn look_at(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        projection: Projection<N>,
    ) -> Option<Self> {
        let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let cross = |a: [f32; 3], b: [f32; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let norm = |a: [f32; 3]| {
            let l = Scalar::sqrt(dot(a, a));
            (l > 1e-12).then(|| [a[0] / l, a[1] / l, a[2] / l])
        };
        let back = norm(sub(eye, target))?; // view +z points from the target to the eye
        let right = norm(cross(up, back))?;
        let up = cross(back, right);
        let view = Affine::from_f32([
            [right[0], right[1], right[2], -dot(right, eye)],
            [up[0], up[1], up[2], -dot(up, eye)],
            [back[0], back[1], back[2], -dot(back, eye)],
        ])?;
        Some(Camera { view, projection })
    }

    /// The same as [`Projection::perspective`] (a projection, for [`Camera::look_at`]).
    pub fn perspective(fov_y: f32, near: f32, far: f32) -> Option<Projection<N>> {
        Projection::perspective(fov_y, near, far)
    }

    /// The same as [`Projection::perspective_with`].
    pub fn perspective_with(
        math: crate::math::MathLib,
        fov_y: f32,
        near: f32,
        far: f32,
    ) -> Option<Projection<N>> {
        Projection::perspective_with(math, fov_y, near, far)
    }
}

impl<N: Scalar> Projection<N> {
    /// A perspective projection from a vertical field of view in radians (tangent by libm in
    /// f32, from exact integer sines in fixed point, see [`crate::math::MathLib::Libm`];
    /// [`Projection::perspective_with`] takes micromath's, cheaper and about 1 % off). `None`
    /// if a value does not fit the number format.
    ///
    /// ```
    /// use zrow::{Camera, Projection, Q16_16};
    /// let p = Projection::<Q16_16>::perspective(1.0, 0.1, 20.0).unwrap();
    /// let camera = Camera::look_at([0.0, 0.0, 4.0], [0.0; 3], [0.0, 1.0, 0.0], p).unwrap();
    /// assert_eq!(camera.projection, p);
    /// ```
    pub fn perspective(fov_y: f32, near: f32, far: f32) -> Option<Self> {
        Self::perspective_with(crate::math::MathLib::Libm, fov_y, near, far)
    }

    /// [`Projection::perspective`] with the tangent from `math`.
    pub fn perspective_with(
        math: crate::math::MathLib,
        fov_y: f32,
        near: f32,
        far: f32,
    ) -> Option<Self> {
        let focal = if N::EXACT_STEPS {
            if math == crate::math::MathLib::Libm {
                // cos/sin of the half angle in integers, exact to 2^-30 each
                // (`number::sin_cos_q31`): no float trigonometry in a fixed-point program.
                let (s, c) = crate::number::sin_cos_q31(fov_y * 0.5)?;
                if s == 0 {
                    return None;
                }
                // c/s in units of 2^-31, rounded; |c| ≤ 2^31 so |c|·2^31 fits.
                let q = ((c.abs() << 31) + s.abs() / 2) / s.abs() * (c.signum() * s.signum());
                N::from_scaled(q, 31)?
            } else {
                N::from_f32(1.0 / crate::math::MathLib::Micromath.tan(fov_y * 0.5))?
            }
        } else {
            N::from_f32(1.0 / math.tan(fov_y * 0.5))?
        };
        Some(Projection::Perspective {
            focal,
            near: N::from_f32(near)?,
            far: N::from_f32(far)?,
        })
    }

    /// An orthographic projection showing `half_height` world units above and below the
    /// screen's centre. `None` if a value does not fit the number format.
    pub fn orthographic(half_height: f32, near: f32, far: f32) -> Option<Self> {
        Some(Projection::Orthographic {
            half_height: N::from_f32(half_height)?,
            near: N::from_f32(near)?,
            far: N::from_f32(far)?,
        })
    }
}

/// One directional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light<N> {
    /// Direction towards the light, in world space (need not be unit length).
    pub direction: Vec3<N>,
    /// Ambient fraction 0..=1 of the face colour that unlit faces keep.
    pub ambient: N,
}

/// A scene in model mode: objects, a camera, a light. Faces are flat (Lambert) shaded.
#[derive(Clone, Copy, Debug)]
pub struct ModelScene<'a, N, I = u16> {
    /// Objects, drawn in order (earlier wins depth ties).
    pub objects: &'a [Object<'a, N, I>],
    /// The camera.
    pub camera: Camera<N>,
    /// The light.
    pub light: Light<N>,
}

/// A scene whose vertices are already in screen space: x right and y down in pixels, z depth
/// (smaller is nearer), projected orthographically along z, each face in its own colour.
#[derive(Clone, Copy, Debug)]
pub struct ScreenScene<'a, N, I = u16> {
    /// The mesh.
    pub mesh: Mesh<'a, N, I>,
}

/// A scene in screen space whose vertices are already snapped to the sub-pixel grid
/// ([`RasterVertex`]: x right and y down in sub-pixels of `subpixel_bits` bits, z depth,
/// smaller nearer), each face in its own colour: the [`ScreenScene`] of the same positions
/// unsnapped, drawn the same, but lent to the renderer ([`Scene::lent_vertices`]) — the
/// scan-line method reads its vertices where they are (in flash, or wherever the application
/// keeps them) instead of copying them into its vertex buffer, so it needs none
/// ([`crate::Requirements::vertices`] is 0: 12 bytes a vertex less in a 32-bit format).
///
/// It is not clipped: every vertex a face uses must lie within the guard band,
/// [`GUARD_BAND`](crate::raster::GUARD_BAND) pixels around the frame
/// ([`Error::OutsideGuardBand`]); `subpixel_bits` must be the frame's
/// ([`Config::subpixel_bits`], else [`Error::BadConfig`]); a face of more than
/// [`INDEXED_CORNERS`] corners lists consecutive vertices (`i, i + 1, …`, else
/// [`Error::Unsupported`]). Hidden-line frames ([`crate::shading::Shading::Facets`]) are
/// drawn from a [`ScreenScene`] ([`Error::Unsupported`]).
///
/// ```
/// use zrow::raster::RasterVertex;
/// use zrow::{Config, Face, Faces, FrameBuffer, Q16_16, Scanline, SnappedScene, Vec3};
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
///
/// let cfg = Config::screen(8, 8);
/// let snap = |x: f32, y: f32, z: f32| {
///     let p = Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
///     RasterVertex::snapped(&p, cfg.subpixel_bits).unwrap()
/// };
/// let vertices = [snap(0.5, 0.5, 1.0), snap(7.5, 0.5, 1.0), snap(0.5, 7.5, 1.0)];
/// let faces = [Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 }];
/// let scene = SnappedScene {
///     vertices: &vertices,
///     faces: Faces::List(&faces),
///     subpixel_bits: cfg.subpixel_bits,
/// };
/// // No vertex buffer (V = 0): the renderer reads the scene's vertices.
/// let mut renderer = Scanline::<Q16_16, 8, 0, 1, 1>::new();
/// let mut pixels = [Rgb565::BLACK; 8 * 8];
/// renderer.render(&scene, &cfg, &mut FrameBuffer::new(&mut pixels, 8)).unwrap();
/// assert_eq!(pixels[8 + 1], Rgb565::RED);
/// assert_eq!(zrow::requirements(&scene, &cfg).unwrap().vertices, 0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct SnappedScene<'a, N, I = u16> {
    /// The vertices, snapped to `subpixel_bits` sub-pixel bits.
    pub vertices: &'a [RasterVertex<N>],
    /// The faces: a list of [`Face`]s, or triangles of one colour ([`Faces`]).
    pub faces: Faces<'a, I>,
    /// The sub-pixel bits the vertices are snapped to: the frame's.
    pub subpixel_bits: u8,
}

/// Polygons with at most this many corners are handed over by index
/// ([`Polygon::corners`]); geometry hands larger ones over as a run of consecutive slots of the
/// vertex buffer, so a renderer can keep any polygon in a few bytes.
pub const INDEXED_CORNERS: usize = 4;

/// Where geometry puts the vertices it projects and snaps, borrowed from the renderer for one
/// frame: first one slot per vertex of each object's mesh (every shared vertex transformed,
/// projected and snapped once per object per frame, whatever number of faces use it), then
/// the vertices clipping makes and the runs of polygons with more than [`INDEXED_CORNERS`]
/// corners.
///
/// With too little room geometry still works, face by face, handing polygons over in scratch
/// of its own ([`Polygon::cached`] is then `false`); [`VertexBuffer::needed`] says how many
/// slots the frame would have used.
#[derive(Debug)]
pub struct VertexBuffer<'a, N> {
    slots: &'a mut [RasterVertex<N>],
    len: usize,
    needed: usize,
}

impl<'a, N: Copy> VertexBuffer<'a, N> {
    /// An empty buffer over `slots`.
    pub fn new(slots: &'a mut [RasterVertex<N>]) -> Self {
        VertexBuffer {
            slots,
            len: 0,
            needed: 0,
        }
    }
    /// Slots in use.
    pub fn len(&self) -> usize {
        self.len
    }
    /// Whether no slot is in use.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    /// Slots the frame would have used with room for all (at least [`VertexBuffer::len`]).
    pub fn needed(&self) -> usize {
        self.needed
    }
    /// The vertices written so far.
    pub fn as_slice(&self) -> &[RasterVertex<N>] {
        &self.slots[..self.len]
    }
    /// Appends `v` as a run of consecutive slots and returns the first one's index, or `None`
    /// without room (counted as needed either way): for a [`Scene`] of one's own that hands
    /// over polygons already projected, which renderers that keep polygons for the frame (the
    /// scan-line method) want [`Polygon::cached`] in this buffer.
    pub fn push(&mut self, v: &[RasterVertex<N>]) -> Option<u32> {
        let start = self.claim(v.len())?;
        self.slots_from(start)[..v.len()].copy_from_slice(v);
        u32::try_from(start).ok()
    }
    /// Claims `n` slots: their first index, or `None` without room (counted as needed
    /// either way).
    pub(crate) fn claim(&mut self, n: usize) -> Option<usize> {
        self.needed += n;
        let start = self.len;
        (self.slots.len() - start >= n).then(|| {
            self.len += n;
            start
        })
    }
    /// Counts `n` slots as needed without claiming them (a polygon handed over in scratch that
    /// a buffer with room would have kept).
    pub(crate) fn claim_none(&mut self, n: usize) {
        self.needed += n;
    }
    /// The claimed slots from `start`.
    pub(crate) fn slots_from(&mut self, start: usize) -> &mut [RasterVertex<N>] {
        &mut self.slots[start..self.len]
    }
}

/// One polygon from geometry: clipped, projected and snapped, with its colour.
#[derive(Clone, Copy, Debug)]
pub struct Polygon<'a, N> {
    /// The vertices it refers to: the frame's [`VertexBuffer`] so far, or all the vertices
    /// the scene lends ([`Scene::lent_vertices`]), when [`Polygon::cached`]; else scratch
    /// valid for this call only.
    pub vertices: &'a [RasterVertex<N>],
    /// Its corners in order (either winding), as indices into `vertices`. When `cached`, a
    /// polygon with more than [`INDEXED_CORNERS`] corners has them consecutive.
    pub corners: &'a [u32],
    /// Whether `vertices` is the frame's buffer or the scene's lent vertices, so that a
    /// renderer may keep `corners` for the rest of the frame (else it must copy what it
    /// keeps; the scan-line method, which keeps polygons by slot, refuses such a polygon
    /// when its buffer has room: [`crate::Error::NotInFrame`]).
    pub cached: bool,
    /// Twice its signed area on the sub-pixel grid, exact (positive: clockwise on the display),
    /// as [`crate::raster::signed_area2`] gives it: geometry has it from culling.
    pub area2: i64,
    /// Its colour after shading: under [`Shading::Gouraud`](crate::shading::Shading::Gouraud),
    /// the face's own colour, which `intensity` then scales pixel by pixel.
    pub color: Rgb565,
    /// Smooth shading's intensity over the polygon, or `None` (flat: `color` everywhere).
    pub intensity: Option<IntensityPlane<N>>,
    /// Its opacity (255 = opaque), from [`Face::alpha`].
    pub alpha: u8,
    /// Index of the face in the scene (objects in order, faces in order; for errors).
    pub face: u32,
}

/// A smooth-shaded polygon's intensity: a plane over the screen like its depth
/// ([`DepthPlane`], the same exact arithmetic: referenced at a pixel, stepped by exact
/// increments, so every method gets the same bits at a pixel), whose value at a pixel centre
/// is the **level** `0..=255` its colour is scaled by there ([`Scalar::to_level`], then
/// [`crate::raster::shade_level`], or [`crate::raster::shade_level_dithered`] if `dither`).
/// Levels rather than a 0..=1 fraction keep 8 more bits
/// of the gradient in Q24.8. Geometry fits it through the polygon's snapped corners and the
/// intensities its vertices were lit with (Gouraud's interpolation; for a triangle exactly
/// the linear interpolation of its three corners).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntensityPlane<N> {
    /// The levels over the screen.
    pub levels: DepthPlane<N>,
    /// Whether each pixel's channels are dithered to Rgb565 (see
    /// [`Shading::Gouraud`](crate::shading::Shading::Gouraud)).
    pub dither: bool,
}

impl<N: Copy> Polygon<'_, N> {
    /// Corner `k`, or `None` past the last corner or for a corner beyond `vertices` (which
    /// only a [`Scene`] of one's own can hand over).
    ///
    /// ```
    /// use zrow::raster::RasterVertex;
    /// use zrow::scene::Polygon;
    /// let v = [RasterVertex { x: 3, y: 4, z: 0.5f32 }];
    /// let p = Polygon {
    ///     vertices: &v, corners: &[0, 7], cached: false, area2: 0,
    ///     color: zrow::Rgb565::new(31, 0, 0), intensity: None, alpha: 255, face: 0,
    /// };
    /// assert_eq!(p.vertex(0), Some(v[0]));
    /// assert_eq!(p.vertex(1), None); // corner 7 of a polygon over one vertex
    /// assert_eq!(p.vertex(2), None); // past its corners
    /// ```
    #[inline]
    pub fn vertex(&self, k: usize) -> Option<RasterVertex<N>> {
        let index = *self.corners.get(k)?;
        self.vertices.get(index as usize).copied()
    }
    /// [`Error::IndexOutOfRange`] for its first corner beyond `vertices`, if one is.
    pub(crate) fn corner_error(&self) -> Option<Error> {
        let len = self.vertices.len();
        let index = *self.corners.iter().find(|&&c| c as usize >= len)?;
        Some(Error::IndexOutOfRange {
            face: self.face,
            index,
        })
    }
    /// Its corners gathered into a [`RasterPolygon`] (a copy); for more than
    /// [`crate::raster::MAX_POLYGON_VERTICES`] corners [`Error::TooManyVertices`], for a
    /// corner beyond `vertices` [`Error::IndexOutOfRange`] (geometry makes neither: only a
    /// [`Scene`] of one's own can).
    pub fn to_raster(&self) -> Result<RasterPolygon<N>, Error> {
        let mut vertices = heapless::Vec::new();
        let face = self.face;
        for &index in self.corners {
            // Geometry's corners are always in range; a scene of its own may not be.
            let v = self
                .vertices
                .get(index as usize)
                .ok_or(Error::IndexOutOfRange { face, index })?;
            vertices
                .push(*v)
                .map_err(|_| Error::TooManyVertices { face })?;
        }
        Ok(RasterPolygon {
            vertices,
            color: self.color,
            alpha: self.alpha,
            face: self.face,
        })
    }
}

/// Anything that can feed polygons to a renderer: runs geometry and calls `f` with every
/// polygon that survives it, in scene order.
pub trait Scene<N: Scalar> {
    /// Streams the scene's polygons, clipped, projected and snapped for `cfg`, writing the
    /// vertices into `vertices`. Model scenes drop back faces here when `cfg.cull` says so (by
    /// the winding of the snapped vertices, the rule [`crate::raster::outline`] applies), so
    /// that culled faces cost no lighting.
    fn polygons(
        &self,
        cfg: &Config,
        vertices: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error>;

    /// The snapped vertices the scene keeps for the whole frame and hands its polygons over
    /// in, if it does ([`Polygon::vertices`] this very slice): a renderer that keeps polygons
    /// for the frame (the scan-line method) then reads them where they are, instead of
    /// having geometry copy them into its vertex buffer. `None` (the default): the scene
    /// writes them into the buffer ([`Scene::polygons`]).
    fn lent_vertices(&self) -> Option<&[RasterVertex<N>]> {
        None
    }

    /// How stored depth maps back to view distance under `cfg`, for stages after visibility
    /// (depth cueing). `None` if the scene has no notion of distance (then shading is flat).
    fn view_depth(&self, cfg: &Config) -> Option<crate::geometry::ViewDepth<N>> {
        let _ = cfg;
        None
    }
}
