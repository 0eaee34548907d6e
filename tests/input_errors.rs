//! Bad input gets an error naming the element, field or particle.

use cloth::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, MeshError, ParamError, Pin, SimulationBuilder, TensileLaw,
};
use nalgebra::Vector2;

fn square() -> (Vec<Vec3>, Vec<Vector2<f64>>) {
    let uv = vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(0.0, 1.0),
    ];
    (uv.iter().map(|p| Vec3::new(p.x, p.y, 0.0)).collect(), uv)
}

#[test]
fn malformed_meshes_are_refused_with_the_element_named() {
    let (x, uv) = square();
    let err = ClothMesh::new(x.clone(), uv.clone(), vec![[0, 1, 2], [0, 2, 9]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::IndexOutOfRange {
            triangle: 1,
            index: 9,
            vertex_count: 4
        }
    );
    assert!(err.to_string().contains("triangle 1"));

    let mut flat_uv = uv.clone();
    flat_uv[2] = Vector2::new(0.5, 0.0); // triangle 0 collapses in uv
    let err = ClothMesh::new(x.clone(), flat_uv, vec![[0, 1, 2], [0, 2, 3]]).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::DegenerateTriangle {
                triangle: 0,
                space: "uv",
                ..
            }
        ),
        "{err}"
    );

    let mut line = x.clone();
    line[3] = Vec3::new(0.5, 0.5, 0.0); // triangle 1 collapses in 3D
    let err = ClothMesh::new(line, uv.clone(), vec![[0, 1, 2], [0, 2, 3]]).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::DegenerateTriangle {
                triangle: 1,
                space: "3D",
                ..
            }
        ),
        "{err}"
    );

    let (mut x5, mut uv5) = (x.clone(), uv.clone());
    x5.push(Vec3::new(0.5, 0.5, 1.0));
    uv5.push(Vector2::new(0.5, -1.0));
    let err = ClothMesh::new(x5, uv5, vec![[0, 1, 2], [0, 2, 3], [0, 4, 2]]).unwrap_err();
    assert_eq!(err, MeshError::NonManifoldEdge { a: 0, b: 2, count: 3 });

    let mut nan = x.clone();
    nan[2].y = f64::NAN;
    let err = ClothMesh::new(nan, uv.clone(), vec![[0, 1, 2], [0, 2, 3]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::NonFinite {
            vertex: 2,
            field: "position"
        }
    );

    let err = ClothMesh::new(x.clone(), uv.clone(), vec![[0, 1, 2]]).unwrap_err();
    assert_eq!(err, MeshError::UnusedVertex { vertex: 3 });
    assert_eq!(ClothMesh::new(x, uv, vec![]).unwrap_err(), MeshError::Empty);
    assert!(matches!(
        GridBuilder::new(1, 5).build(),
        Err(MeshError::BadGrid { .. })
    ));
}

#[test]
fn impossible_parameters_name_the_field() {
    let mesh = GridBuilder::new(4, 4).build().unwrap();
    let mut fabric = Fabric::cotton_like();
    fabric.area_density = -0.1;
    let err = SimulationBuilder::new(mesh.clone(), fabric).build().unwrap_err();
    assert!(err.to_string().contains("area_density"), "{err}");

    let mut fabric = Fabric::cotton_like();
    fabric.weft = TensileLaw::PowerLaw {
        strain_ref: 0.1,
        tension_ref: 10.0,
        exponent: 0.5,
    };
    let err = SimulationBuilder::new(mesh.clone(), fabric).build().unwrap_err();
    assert!(err.to_string().contains("weft"), "{err}");

    let err = SimulationBuilder::new(mesh.clone(), Fabric::cotton_like())
        .time_step(0.0)
        .build()
        .unwrap_err();
    assert!(err.to_string().contains("time_step"), "{err}");

    let err = SimulationBuilder::new(mesh.clone(), Fabric::cotton_like())
        .pin(Pin::fixed(99))
        .build()
        .unwrap_err();
    assert_eq!(
        err,
        ParamError::PinOutOfRange {
            particle: 99,
            count: 16
        }
    );

    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .build()
        .unwrap();
    assert!(sim.set_velocities(&[Vec3::zeros(); 3]).is_err());
    assert!(sim.set_velocities(&[Vec3::new(f64::NAN, 0.0, 0.0); 16]).is_err());
}

#[test]
fn scenes_too_large_to_build_are_refused_before_anything_is_built() {
    use cloth::scene_file::SceneFile;
    let scene = |cloth: &str, extra: &str| {
        let text = format!("{extra}\n[cloth]\n{cloth}\n[fabric]\npreset = \"cotton_poplin\"\n");
        SceneFile::from_toml_str(&text, "big.toml").unwrap()
    };
    let dir = std::path::Path::new(".");
    for cloth in [
        "grid = { nx = 100000, ny = 100000, size = [1, 1] }",
        "cusick = { edge_length = 1e-6 }",
        "cantilever = { overhang = 0.1, cells = 1000000000 }",
    ] {
        let e = scene(cloth, "")
            .prepare("big.toml", dir)
            .err()
            .expect(cloth)
            .to_string();
        assert!(
            e.contains("over the limit of 2000000 (max_triangles)"),
            "{cloth}: {e}"
        );
    }
    // The limit is the scene's to set.
    let small = "grid = { nx = 101, ny = 101, size = [1, 1] }";
    assert!(scene(small, "").prepare("big.toml", dir).is_ok());
    let e = scene(small, "max_triangles = 10000")
        .prepare("big.toml", dir)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("about 2.00e4 triangles, over the limit of 10000"),
        "{e}"
    );
}
