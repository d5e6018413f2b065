//! Typed errors. Every one is raised before the first row leaves the renderer, so a failed
//! frame never leaves a half-drawn picture behind.

/// A table whose capacity a scene can exceed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Table {
    /// The polygon table (polygons that survive culling and touch the screen).
    Polygons,
    /// The edge table (edges that cross a sample row on screen).
    Edges,
    /// The vertex buffer (the scan-line method: every vertex of the scene's meshes once, plus
    /// what clipping makes; see [`crate::Requirements::vertices`]).
    Vertices,
    /// The active list (polygons spanning one row; twice as many active edges).
    ActivePolygons,
    /// The row buffers (`depth[x]`, `intensity[x]`): the frame is wider than they are.
    RowWidth,
    /// A whole-frame or band buffer (z-buffer rows, tiled z-buffer band): the frame is
    /// taller or wider than it holds.
    FrameBuffer,
    /// Pieces (polygons and the parts splitting made of them): depth-sort and BSP.
    Pieces,
    /// BSP tree depth (the build's explicit stack).
    BspDepth,
    /// Warnock's potentially-visible lists, summed over the levels of subdivision.
    VisibleList,
    /// Translucent fragments in one row (A-buffer).
    Fragments,
}

/// What went wrong, and what to do about it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// The scene needs more room in `table` than the renderer has: build it with a capacity of
    /// at least `needed` (see [`crate::requirements()`]).
    Capacity {
        /// Which table.
        table: Table,
        /// What this scene needs.
        needed: u32,
        /// What the renderer has.
        capacity: u32,
    },
    /// Face `face` refers to vertex `index`, which the mesh does not have: fix the face list.
    IndexOutOfRange {
        /// Face number in the scene (objects in order, faces in order).
        face: u32,
        /// The offending index.
        index: u32,
    },
    /// Face `face` has fewer than 3 vertices: drop it or complete it.
    TooFewVertices {
        /// Face number.
        face: u32,
    },
    /// Face `face` has more than [`crate::raster::MAX_FACE_VERTICES`] vertices: split it.
    TooManyVertices {
        /// Face number.
        face: u32,
    },
    /// A vertex of face `face` is NaN, infinite or outside the number format's range (or a
    /// transform pushed it there): fix the data or scale the model down.
    NonFinite {
        /// Face number.
        face: u32,
    },
    /// A vertex of face `face` of a [`crate::SnappedScene`] lies outside the guard band
    /// ([`crate::raster::GUARD_BAND`] pixels around the frame), which such a scene does not
    /// clip: move it in, or draw the scene unsnapped ([`crate::ScreenScene`] clips).
    OutsideGuardBand {
        /// Face number.
        face: u32,
    },
    /// Face `face` is not convex (its outline goes down and up more than once, or clipping it
    /// made more corners than a convex face can have): split it into triangles.
    NotConvex {
        /// Face number.
        face: u32,
    },
    /// A [`crate::Scene`] of one's own handed face `face` over on vertices that are neither
    /// the frame's vertex buffer nor the scene's lent vertices
    /// ([`crate::scene::Polygon::cached`] false, or said but not so), though the buffer had
    /// room: a renderer that keeps polygons for the whole frame by vertex slot (the scan-line
    /// method) cannot keep it. Write its vertices with
    /// [`crate::scene::VertexBuffer::push`], or lend them all
    /// ([`crate::Scene::lent_vertices`]).
    NotInFrame {
        /// Face number.
        face: u32,
    },
    /// A mesh has `normals` precomputed normals for its `faces` faces: give exactly one per
    /// face, or none (then model mode computes them).
    Normals {
        /// Faces in the mesh.
        faces: u32,
        /// Normals in the mesh.
        normals: u32,
    },
    /// A mesh has `normals` per-vertex normals for its `vertices` vertices: give exactly one
    /// per vertex, or none (then its faces are drawn flat).
    VertexNormals {
        /// Vertices in the mesh.
        vertices: u32,
        /// Vertex normals in the mesh.
        normals: u32,
    },
    /// A mesh of triangles ([`crate::Faces::Triangles`]) has `colors` colours for its `faces`
    /// triangles: give one per triangle, or one for all.
    Colors {
        /// Triangles in the mesh.
        faces: u32,
        /// Colours in the mesh.
        colors: u32,
    },
    /// The configuration is impossible: size 0 or above `MAX_VIEWPORT`, sub-pixel bits
    /// outside 1..=8, or depth-cue parameters that are not finite, not `near < far`, or a
    /// `floor` outside 0..=1, or facets ([`crate::shading::Shading::Facets`]) on a background
    /// that is not black.
    BadConfig,
    /// This method does not implement `feature`: pick a method that does (the message says
    /// which) or another setting.
    Unsupported {
        /// What is not supported, and where it is.
        feature: &'static str,
    },
}

impl Table {
    /// The const parameter of the renderer type that sets this capacity, as the methods name
    /// it (`Scanline<N, W, V, P, A>`, `ZBuffer<N, W, H>`, the polygon table's `P` and `E`, the
    /// pieces' `Q`, the BSP stack's `D`, Warnock's list `L`, the A-buffer's fragments `F`).
    pub fn parameter(&self) -> &'static str {
        match self {
            Table::Polygons => "P",
            Table::Edges => "E",
            Table::Vertices => "V",
            Table::ActivePolygons => "A",
            Table::RowWidth => "W",
            Table::FrameBuffer => "W and H",
            Table::Pieces => "Q",
            Table::BspDepth => "D",
            Table::VisibleList => "L",
            Table::Fragments => "F",
        }
    }
}

impl core::fmt::Display for Table {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Table::Polygons => "polygon table",
            Table::Edges => "edge table",
            Table::Vertices => "vertex buffer",
            Table::ActivePolygons => "active list",
            Table::RowWidth => "row buffer",
            Table::FrameBuffer => "frame buffer",
            Table::Pieces => "piece table",
            Table::BspDepth => "BSP stack",
            Table::VisibleList => "potentially-visible list",
            Table::Fragments => "fragment list",
        })
    }
}

impl Error {
    /// The face the error is about (its number in the scene: objects in order, faces in
    /// order), for an error about one face; a loader uses it to name the line the face came
    /// from.
    pub fn face(&self) -> Option<u32> {
        match *self {
            Error::IndexOutOfRange { face, .. }
            | Error::TooFewVertices { face }
            | Error::TooManyVertices { face }
            | Error::NonFinite { face }
            | Error::OutsideGuardBand { face }
            | Error::NotConvex { face }
            | Error::NotInFrame { face } => Some(face),
            _ => None,
        }
    }
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Error::Capacity {
                table,
                needed,
                capacity,
            } => write!(
                f,
                "{table} holds {capacity} but this scene needs {needed}: raise that capacity \
                 (the renderer's const parameter {} to at least {needed})",
                table.parameter()
            ),
            Error::IndexOutOfRange { face, index } => {
                write!(f, "face {face}: vertex index {index} out of range")
            }
            Error::TooFewVertices { face } => write!(f, "face {face}: fewer than 3 vertices"),
            Error::TooManyVertices { face } => write!(
                f,
                "face {face}: more than {} vertices",
                crate::raster::MAX_FACE_VERTICES
            ),
            Error::NonFinite { face } => write!(
                f,
                "face {face}: coordinate not finite or outside the number format"
            ),
            Error::OutsideGuardBand { face } => write!(
                f,
                "face {face}: snapped vertex outside the guard band ({} pixels around the frame)",
                crate::raster::GUARD_BAND
            ),
            Error::NotConvex { face } => write!(f, "face {face}: not convex"),
            Error::NotInFrame { face } => write!(
                f,
                "face {face}: handed over on vertices outside the frame's vertex buffer and the \
                 scene's lent vertices, which a renderer that keeps polygons by slot cannot keep"
            ),
            Error::Normals { faces, normals } => write!(
                f,
                "mesh has {normals} normals for {faces} faces: give one per face or none"
            ),
            Error::VertexNormals { vertices, normals } => write!(
                f,
                "mesh has {normals} vertex normals for {vertices} vertices: give one per vertex or none"
            ),
            Error::Colors { faces, colors } => write!(
                f,
                "mesh has {colors} colours for {faces} triangles: give one per triangle or one for all"
            ),
            Error::BadConfig => write!(
                f,
                "bad configuration: size must be 1..=2048, sub-pixel bits 1..=8, depth cue near < far with floor 0..=1, facets on black"
            ),
            Error::Unsupported { feature } => write!(f, "not supported by this method: {feature}"),
        }
    }
}

/// A render that failed: either the scene (before any row was sent) or the sink.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RenderError<E> {
    /// The scene or configuration was rejected; no row was sent.
    Scene(Error),
    /// The sink failed while rows were being sent.
    Sink(E),
}

impl<E> From<Error> for RenderError<E> {
    fn from(e: Error) -> Self {
        RenderError::Scene(e)
    }
}

impl<E: core::fmt::Display> core::fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Scene(e) => write!(f, "scene rejected before any row: {e}"),
            RenderError::Sink(e) => write!(f, "row sink failed: {e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A render error prints as the scene's error or the sink's, saying which.
    #[test]
    fn render_errors_print() {
        let scene: RenderError<core::convert::Infallible> =
            RenderError::Scene(Error::NotConvex { face: 7 });
        let mut buf = [0u8; 64];
        let mut w = Buf(&mut buf, 0);
        core::fmt::write(&mut w, format_args!("{scene}")).unwrap();
        assert_eq!(
            w.text(),
            "scene rejected before any row: face 7: not convex"
        );
        let sink: RenderError<&str> = RenderError::Sink("SPI timeout");
        let mut w = Buf(&mut buf, 0);
        core::fmt::write(&mut w, format_args!("{sink}")).unwrap();
        assert_eq!(w.text(), "row sink failed: SPI timeout");
    }

    struct Buf<'a>(&'a mut [u8], usize);
    impl Buf<'_> {
        fn text(&self) -> &str {
            core::str::from_utf8(&self.0[..self.1]).unwrap()
        }
    }
    impl core::fmt::Write for Buf<'_> {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            let end = self.1 + s.len();
            self.0
                .get_mut(self.1..end)
                .ok_or(core::fmt::Error)?
                .copy_from_slice(s.as_bytes());
            self.1 = end;
            Ok(())
        }
    }
}
