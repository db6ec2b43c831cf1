//! The sphere domain: a built icosahedron and bunny.off (closed genus-0) onto the unit sphere,
//! the octahedral unfold, an open mesh refused, the sphere phases and parameters.
mod common;

use std::sync::atomic::{AtomicUsize, Ordering};

use raps::{Domain, Monitor, Param, Parameterization, Phase, Settings, SphereMethod, SphereUv};
use raps::{Stats, Status};

fn sphere_settings() -> Settings {
    let mut settings = Settings::new().unwrap();
    settings.set_domain(Domain::SPHERE).unwrap();
    assert_eq!(settings.domain().unwrap(), Domain::SPHERE);
    settings
}

fn mesh_of(xyz: &[f64], indices: &[u32]) -> raps::Mesh {
    raps::Mesh::from_f64(xyz, indices).expect("a valid mesh")
}

fn det(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

fn signed_area(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> f32 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// What the binding must hand over of a sphere map: one unit point per input vertex, every
/// input triangle counter-clockwise seen from outside on them, the input triangles and an
/// identity remap; returns the statistics.
fn check_sphere_map(map: &Parameterization, xyz: &[f64], indices: &[u32]) -> Stats {
    let n = xyz.len() / 3;
    let points = map.sphere_points_f64().unwrap();
    assert_eq!(points.len(), n);
    for (i, p) in points.iter().enumerate() {
        let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((norm - 1.0).abs() <= 1e-9, "point {} has norm {}", i, norm);
    }
    for (t, v) in indices.chunks(3).enumerate() {
        let (a, b, c) = (
            points[v[0] as usize],
            points[v[1] as usize],
            points[v[2] as usize],
        );
        assert!(det(a, b, c) > 0.0, "triangle {} folded on the sphere", t);
    }
    for (single, double) in map.sphere_points().unwrap().iter().zip(&points) {
        for c in 0..3 {
            assert!((f64::from(single[c]) - double[c]).abs() < 1e-6);
        }
    }
    let stats = map.stats().unwrap();
    assert_eq!(stats.flipped_triangles, 0);
    assert!(stats.relaxation_sweeps > 0);
    assert_eq!(stats.vertex_count as usize, n);
    assert_eq!(stats.chart_count, 1);
    assert_eq!(stats.utilization, 0.0); // no uvs, no uv area
    assert_eq!(map.indices().unwrap(), indices);
    let identity: Vec<u32> = (0..n as u32).collect();
    assert_eq!(map.vertex_remap().unwrap(), identity);
    stats
}

#[test]
fn an_icosahedron_maps_onto_the_unit_sphere() {
    let (xyz, indices) = common::icosahedron();
    let mesh = mesh_of(&xyz, &indices);
    let settings = sphere_settings();
    assert_eq!(settings.sphere_method().unwrap(), SphereMethod::ROBUST);
    assert_eq!(settings.sphere_uv().unwrap(), SphereUv::NONE);
    let map = raps::parameterize(&mesh, Some(&settings)).unwrap();
    let stats = check_sphere_map(&map, &xyz, &indices);
    // The area monitor's iteration reached through 2 relaxations (sphere_alpha_steps).
    assert_eq!(stats.adaptive_solves, 2);
    // Without the octahedral unfold a sphere map has no uvs, and says so.
    let error = map.uvs().unwrap_err();
    assert_eq!(error.status(), Status::INVALID_OPERATION);
    assert!(
        error.message().contains("OCTAHEDRAL") && error.message().contains("sphere_points"),
        "{}",
        error
    );
    assert_eq!(
        map.uvs_f64().unwrap_err().status(),
        Status::INVALID_OPERATION
    );
    let mut short = [[0.0f32; 3]; 11];
    let error = map.copy_sphere_points_into(&mut short).unwrap_err();
    assert_eq!(error.status(), Status::INVALID_ARGUMENT);
    assert!(error.message().contains("12"), "{}", error);
}

#[test]
fn the_literal_method_keeps_the_icosahedrons_gauss_map() {
    // Its Gauss map, which the symmetric icosahedron keeps: vertex i's point is its position
    // normalised, x, y, z in that order.
    let (xyz, indices) = common::icosahedron();
    let mut settings = sphere_settings();
    settings
        .set_sphere_method(SphereMethod::LITERAL)
        .unwrap()
        .set_monitor(Monitor::NONE)
        .unwrap();
    let map = raps::parameterize(&mesh_of(&xyz, &indices), Some(&settings)).unwrap();
    check_sphere_map(&map, &xyz, &indices);
    for (p, q) in map.sphere_points_f64().unwrap().iter().zip(xyz.chunks(3)) {
        let norm = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        for c in 0..3 {
            assert!((p[c] - q[c] / norm).abs() < 1e-9, "{:?} vs {:?}", p, q);
        }
    }
}

#[test]
fn a_shared_closed_mesh_maps_bijectively_and_equidistributes_area() {
    let (xyz, indices) = common::read_off("meshes/bunny.off");
    let mesh = mesh_of(&xyz, &indices);
    let mut plain = sphere_settings();
    plain.set_monitor(Monitor::NONE).unwrap();
    let first = raps::parameterize(&mesh, Some(&plain)).unwrap();
    let second = raps::parameterize(&mesh, Some(&sphere_settings())).unwrap();
    let (before, after) = (
        check_sphere_map(&first, &xyz, &indices),
        check_sphere_map(&second, &xyz, &indices),
    );
    assert_eq!(before.adaptive_solves, 0);
    // Spherical area distortion, measured in tests/test_sphere.c: 1.638 -> 0.667.
    assert!(
        after.area_log_mean < 0.5 * before.area_log_mean,
        "{} -> {}",
        before.area_log_mean,
        after.area_log_mean
    );
    assert!(second.phase_ms(Phase::ADAPT) > 0.0);
    // sphere_max_sweeps and sphere_alpha_steps reach the library: 2 adaptive relaxations, at
    // most 3 sweeps in each of the 3 relaxations.
    let mut capped = sphere_settings();
    capped
        .set_sphere_max_sweeps(3)
        .unwrap()
        .set_sphere_alpha_steps(2)
        .unwrap();
    let stats = raps::parameterize(&mesh, Some(&capped))
        .unwrap()
        .stats()
        .unwrap();
    assert_eq!(stats.adaptive_solves, 2);
    assert!(stats.relaxation_sweeps > 0 && stats.relaxation_sweeps <= 9);
    assert!(after.relaxation_sweeps > 9);
}

#[test]
fn the_octahedral_unfold_gives_one_chart_in_the_square() {
    for (xyz, indices) in [common::icosahedron(), common::read_off("meshes/bunny.off")] {
        let n = xyz.len() / 3;
        let mesh = mesh_of(&xyz, &indices);
        let sphere = raps::parameterize(&mesh, Some(&sphere_settings())).unwrap();
        let mut settings = sphere_settings();
        settings.set_sphere_uv(SphereUv::OCTAHEDRAL).unwrap();
        assert_eq!(settings.sphere_uv().unwrap(), SphereUv::OCTAHEDRAL);
        let map = raps::parameterize(&mesh, Some(&settings)).unwrap();
        // The cut's vertices are duplicated: more output vertices than input.
        let count = map.vertex_count();
        assert!(count > n, "{} output vertices for {}", count, n);
        let uvs = map.uvs().unwrap();
        let remap = map.vertex_remap().unwrap();
        let out = map.indices().unwrap();
        let points = map.sphere_points_f64().unwrap();
        let original = sphere.sphere_points_f64().unwrap();
        assert_eq!(
            (uvs.len(), remap.len(), points.len()),
            (count, count, count)
        );
        assert!(uvs
            .iter()
            .all(|uv| uv.iter().all(|&c| (0.0..=1.0).contains(&c))));
        assert_eq!(out.len(), indices.len());
        for (corner, (&o, &i)) in out.iter().zip(&indices).enumerate() {
            assert_eq!(remap[o as usize], i, "corner {}", corner);
        }
        for (t, v) in out.chunks(3).enumerate() {
            let area = signed_area(uvs[v[0] as usize], uvs[v[1] as usize], uvs[v[2] as usize]);
            assert!(area > 0.0, "uv triangle {} counter-clockwise", t);
        }
        for (o, &r) in remap.iter().enumerate() {
            assert_eq!(
                points[o], original[r as usize],
                "output vertex {} at its input vertex's point",
                o
            );
        }
        let stats = map.stats().unwrap();
        assert_eq!(stats.flipped_triangles, 0);
        assert_eq!(stats.vertex_count as usize, count);
        assert_eq!(stats.chart_count, 1);
        assert!(stats.relaxation_sweeps > 0);
        assert!(stats.utilization > 0.0 && stats.utilization <= 1.0);
    }
}

#[test]
fn an_open_mesh_is_refused_with_its_boundary_counted() {
    let (xyz, indices) = common::fan_disk();
    let mesh = mesh_of(&xyz, &indices);
    let mut out = Parameterization::new().unwrap();
    let error = raps::parameterize_into(&mesh, Some(&sphere_settings()), &mut out).unwrap_err();
    assert_eq!(error.status(), Status::OPEN_MESH);
    assert_eq!(format!("{:?}", error.status()), "Status::OPEN_MESH");
    assert!(
        error.message().contains("closed mesh") && error.message().contains("1 boundary loop"),
        "{}",
        error
    );
    assert_eq!(error.name(), raps::status_string(Status::OPEN_MESH));
    assert_ne!(error.name(), "unknown status");
    assert_eq!(out.vertex_count(), 0);
    assert_eq!(
        out.sphere_points().unwrap_err().status(),
        Status::INVALID_OPERATION
    );
    // The disk domain maps the same mesh; its result has uvs but no sphere points.
    raps::parameterize_into(&mesh, None, &mut out).unwrap();
    let error = out.sphere_points_f64().unwrap_err();
    assert_eq!(error.status(), Status::INVALID_OPERATION);
    assert!(error.message().contains("sphere points"), "{}", error);
}

#[test]
fn progress_reports_the_sphere_phases_and_cancels() {
    let (xyz, indices) = common::read_off("meshes/bunny.off");
    let mesh = mesh_of(&xyz, &indices);
    let mut settings = sphere_settings();
    settings.set_threads(2).unwrap();
    let mut calls = Vec::new();
    let (inside, overlaps) = (AtomicUsize::new(0), AtomicUsize::new(0));
    raps::parameterize_with_progress(&mesh, Some(&settings), |phase, fraction| {
        if inside.fetch_add(1, Ordering::SeqCst) > 0 {
            overlaps.fetch_add(1, Ordering::SeqCst);
        }
        calls.push((phase, fraction));
        std::thread::sleep(std::time::Duration::from_millis(1)); // another thread could enter
        inside.fetch_sub(1, Ordering::SeqCst);
        true
    })
    .unwrap();
    // The disk domain's five phases: the initial map and its relaxation, then the adaptive
    // relaxations.
    let mut phases: Vec<Phase> = calls.iter().map(|c| c.0).collect();
    phases.dedup();
    assert_eq!(
        phases,
        [
            Phase::VALIDATE,
            Phase::TOPOLOGY,
            Phase::INITIAL_MAP,
            Phase::ADAPT,
            Phase::METRICS
        ]
    );
    assert_eq!(overlaps.load(Ordering::SeqCst), 0);
    assert!(calls.iter().all(|c| (0.0..=1.0).contains(&c.1)));

    let error =
        raps::parameterize_with_progress(&mesh, Some(&settings), |phase, _| phase < Phase::ADAPT)
            .unwrap_err();
    assert_eq!(error.status(), Status::CANCELLED);
    let map = raps::parameterize(&mesh, Some(&settings)).unwrap();
    assert_eq!(map.vertex_count(), mesh.vertex_count());
}

#[test]
fn sphere_settings_round_trip() {
    // (parameter, name, is_float, min, max, default), as raps_param_info gives them; (0, 1]
    // has the smallest normal double as its lower bound.
    #[rustfmt::skip]
    let expected = [
        (Param::SPHERE_METHOD, "sphere_method", false, 0.0, 1.0, 1.0),
        (Param::SPHERE_UV, "sphere_uv", false, 0.0, 1.0, 0.0),
        (Param::SPHERE_DAMPING, "sphere_damping", true, f64::MIN_POSITIVE, 1.0, 1.0),
        (Param::SPHERE_TOLERANCE, "sphere_tolerance", true, 1e-12, 1.0, 1e-4),
        (Param::SPHERE_MAX_SWEEPS, "sphere_max_sweeps", false, 0.0, 1e7, 0.0),
        (Param::SPHERE_ALPHA_STEPS, "sphere_alpha_steps", false, 1.0, 100.0, 2.0),
    ];
    let defaults = Settings::new().unwrap();
    for (param, name, is_float, min, max, default) in expected {
        let info = Settings::param_info(param).unwrap();
        assert_eq!(
            (info.name, info.is_float, info.min, info.max, info.default),
            (name, is_float, min, max, default)
        );
        let value = if is_float {
            defaults.float(param).unwrap()
        } else {
            defaults.int(param).unwrap() as f64
        };
        assert_eq!(value, default, "{} holds its default", name);
        assert!(
            format!("{:?}", defaults).contains(&format!("{}: ", name)),
            "{}",
            name
        );
    }
    assert_eq!(defaults.sphere_method().unwrap(), SphereMethod::ROBUST);
    assert_eq!(defaults.sphere_uv().unwrap(), SphereUv::NONE);
    assert_eq!(defaults.sphere_damping().unwrap(), 1.0);
    assert_eq!(defaults.sphere_tolerance().unwrap(), 1e-4);
    assert_eq!(defaults.sphere_max_sweeps().unwrap(), 0);
    assert_eq!(defaults.sphere_alpha_steps().unwrap(), 2);
    let domain = Settings::param_info(Param::DOMAIN).unwrap();
    assert_eq!(
        (domain.min, domain.max),
        (f64::from(Domain::DISK.0), f64::from(Domain::ATLAS.0))
    );
    assert!(Domain::DISK < Domain::SPHERE && Domain::SPHERE < Domain::ATLAS);
    assert_eq!(
        format!("{:?}", SphereUv::OCTAHEDRAL),
        "SphereUv::OCTAHEDRAL"
    );

    let mut settings = sphere_settings();
    settings
        .set_sphere_method(SphereMethod::LITERAL)
        .unwrap()
        .set_sphere_uv(SphereUv::OCTAHEDRAL)
        .unwrap()
        .set_sphere_damping(0.5)
        .unwrap()
        .set_sphere_tolerance(1e-6)
        .unwrap()
        .set_sphere_max_sweeps(10_000_000)
        .unwrap()
        .set_sphere_alpha_steps(100)
        .unwrap();
    let copy = settings.try_clone().unwrap();
    assert_eq!(copy.domain().unwrap(), Domain::SPHERE);
    assert_eq!(copy.sphere_method().unwrap(), SphereMethod::LITERAL);
    assert_eq!(copy.sphere_uv().unwrap(), SphereUv::OCTAHEDRAL);
    assert_eq!(copy.sphere_damping().unwrap(), 0.5);
    assert_eq!(copy.sphere_tolerance().unwrap(), 1e-6);
    assert_eq!(copy.sphere_max_sweeps().unwrap(), 10_000_000);
    assert_eq!(copy.sphere_alpha_steps().unwrap(), 100);
    for error in [
        settings.set_sphere_method(SphereMethod(2)).unwrap_err(),
        settings.set_sphere_uv(SphereUv(2)).unwrap_err(),
        settings.set_sphere_damping(0.0).unwrap_err(),
        settings.set_sphere_damping(1.5).unwrap_err(),
        settings.set_sphere_tolerance(1e-13).unwrap_err(),
        settings.set_sphere_tolerance(2.0).unwrap_err(),
        settings.set_sphere_max_sweeps(10_000_001).unwrap_err(),
        settings.set_sphere_alpha_steps(0).unwrap_err(),
        settings.set_sphere_alpha_steps(101).unwrap_err(),
        settings.set_int(Param::SPHERE_DAMPING, 1).unwrap_err(), // a float parameter
    ] {
        assert_eq!(error.status(), Status::INVALID_ARGUMENT);
    }
    let error = settings.set_sphere_alpha_steps(101).unwrap_err();
    assert!(error.message().contains("sphere_alpha_steps"), "{}", error);
    // A failed setter changes nothing.
    assert_eq!(settings.sphere_method().unwrap(), SphereMethod::LITERAL);
    assert_eq!(settings.sphere_uv().unwrap(), SphereUv::OCTAHEDRAL);
    assert_eq!(settings.sphere_damping().unwrap(), 0.5);
    assert_eq!(settings.sphere_tolerance().unwrap(), 1e-6);
    assert_eq!(settings.sphere_max_sweeps().unwrap(), 10_000_000);
    assert_eq!(settings.sphere_alpha_steps().unwrap(), 100);
}
