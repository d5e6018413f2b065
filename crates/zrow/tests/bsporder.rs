//! The precomputed BSP order over convex objects (`zrow::bsporder`): built once for a static
//! scene, it draws what the scan-line method draws from every camera tried, with no depth test;
//! scenes it cannot order are refused when the tree is built.

mod common;
use common::*;
use heapless::Vec as HVec;
use zrow::bsporder::{build, BspOrder, OrderError, OrderNode};
use zrow::{Affine, Camera, Config, Light, Mesh, ModelScene, Object, Scalar, Vec3, Q16_16};

const K: usize = 16;

/// Cubes (unit, from zrow-scenes) at `places`, each turned a little differently.
fn cubes<N: zrow_scenes::Format>(
    mesh: &Mesh<'static, N>,
    places: &[[f32; 3]],
) -> std::vec::Vec<Object<'static, N>> {
    let mesh: &'static Mesh<'static, N> = Box::leak(Box::new(*mesh));
    places
        .iter()
        .enumerate()
        .map(|(k, &t)| Object {
            mesh,
            transform: Affine::rotate_yx_translate(0.3 * k as f32, 0.2 * k as f32, t).unwrap(),
        })
        .collect()
}

/// Eyes around the scene, on a sphere of radius `r` (never inside an object).
fn eyes(r: f32) -> impl Iterator<Item = [f32; 3]> {
    (0..24).map(move |k| {
        let (yaw, pitch) = (0.7 * k as f32, -1.2 + 0.1 * k as f32);
        [
            r * pitch.cos() * yaw.sin(),
            r * pitch.sin(),
            r * pitch.cos() * yaw.cos(),
        ]
    })
}

fn scene<'a, N: Scalar>(objects: &'a [Object<'a, N>], eye: [f32; 3]) -> ModelScene<'a, N> {
    let projection = Camera::<N>::perspective(0.9, 0.5, 40.0).unwrap();
    ModelScene {
        objects,
        camera: Camera::look_at(eye, [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], projection).unwrap(),
        light: Light {
            direction: Vec3::from_f32([0.3, 1.0, 0.5]).unwrap(),
            ambient: N::from_f32(0.2).unwrap(),
        },
    }
}

fn same_as_scanline<N: zrow_scenes::Format>(places: &[[f32; 3]]) {
    let objects = cubes(&zrow_scenes::mesh::<N>("cube").unwrap(), places);
    let mut tree: HVec<OrderNode, K> = HVec::new();
    build(&objects, &mut tree).unwrap();
    assert_eq!(
        tree.len(),
        2 * places.len() - 1,
        "no split: K leaves, K − 1 planes"
    );
    let mut order = Box::new(BspOrder::<N, 128, 64, 256, K>::new(&tree));
    let mut scan = Box::new(Big::<N>::new());
    let cfg = Config::model(128, 96);
    for eye in eyes(9.0) {
        let s = scene(&objects, eye);
        let mut want = Capture::new(128, 96);
        scan.render(&s, &cfg, &mut want).unwrap();
        let mut got = Capture::new(128, 96);
        order.render(&s, &cfg, &mut got).unwrap();
        assert!(want.color == got.color, "{} eye {eye:?}: colour", N::NAME);
        if N::NAME == Q16_16::NAME {
            assert!(want.depth == got.depth, "eye {eye:?}: depth bits");
        }
        assert!(want.drawn() > 200, "eye {eye:?}: the cubes are on screen");
    }
    println!(
        "{} objects, {}: bsp-order RAM {} B (cull-only inside, no depth test), scan-line as built {} B",
        places.len(),
        N::NAME,
        BspOrder::<N, 128, 64, 256, K>::RAM_BYTES,
        Big::<N>::RAM_BYTES
    );
}

#[test]
fn separate_cubes_are_drawn_exactly_from_every_side() {
    let places = [
        [-2.5, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [2.5, 0.3, 0.0],
        [0.0, 2.2, -0.4],
        [0.4, -0.2, 2.5],
        [-1.0, -2.4, -1.5],
    ];
    same_as_scanline::<Q16_16>(&places);
    same_as_scanline::<f32>(&places);
}

#[test]
fn scenes_it_cannot_order_are_refused() {
    let cube = zrow_scenes::mesh::<Q16_16>("cube").unwrap();
    let mut tree: HVec<OrderNode, K> = HVec::new();
    // Two cubes overlapping in space: no plane separates them.
    let overlapping = cubes(&cube, &[[0.0, 0.0, 0.0], [0.4, 0.3, 0.2]]);
    assert_eq!(
        build(&overlapping, &mut tree),
        Err(OrderError::NotSeparable)
    );
    // A torus is not convex.
    let torus = zrow_scenes::mesh::<Q16_16>("mesh1k").unwrap();
    let objects = [
        cubes(&cube, &[[3.0, 0.0, 0.0]])[0],
        Object {
            mesh: &torus,
            transform: Affine::identity(),
        },
    ];
    assert_eq!(build(&objects, &mut tree), Err(OrderError::NotConvex(1)));
    // More objects than room.
    let many = cubes(&cube, &[[0.0; 3]; 3]);
    let mut small: HVec<OrderNode, 2> = HVec::new();
    assert_eq!(build(&many, &mut small), Err(OrderError::Capacity));
    assert_eq!(
        build::<Q16_16, u16, K>(&[], &mut tree),
        Err(OrderError::Capacity)
    );
}

/// A malformed tree (a node pointing at itself) is an error, never an endless walk.
#[test]
fn a_cyclic_tree_is_an_error() {
    let cube = zrow_scenes::mesh::<Q16_16>("cube").unwrap();
    let objects = cubes(&cube, &[[0.0; 3], [3.0, 0.0, 0.0]]);
    let tree = [OrderNode::Split {
        plane: [1.0, 0.0, 0.0, 1.5],
        front: 0,
        back: 0,
    }];
    let mut r = Box::new(BspOrder::<Q16_16, 64, 32, 128, K>::new(&tree));
    let mut cap = Capture::new(64, 48);
    assert!(r
        .render(
            &scene(&objects, [0.0, 2.0, 9.0]),
            &Config::model(64, 48),
            &mut cap
        )
        .is_err());
    assert_eq!(cap.rows_received, 0);
}
