//! Errors, handle ownership and settings of the Rust binding.
mod common;

use raps::{Boundary, Domain, IterationMode, Monitor, Param, Settings, Status, Weights};

#[test]
fn a_closed_mesh_has_no_boundary() {
    let (xyz, indices) = common::icosahedron();
    let mesh = raps::Mesh::from_f64(&xyz, &indices).unwrap();
    let error = raps::parameterize(&mesh, None).unwrap_err();
    assert_eq!(error.status(), Status::NO_BOUNDARY);
    assert!(!error.message().is_empty());
    assert_ne!(error.name(), "unknown status");
    let text = error.to_string();
    assert!(
        text.contains(error.name()) && text.contains(error.message()),
        "{}",
        text
    );
}

#[test]
fn an_index_out_of_range_names_the_index() {
    let (xyz, mut indices) = common::icosahedron();
    indices[11] = 12;
    let mesh = raps::Mesh::from_f64(&xyz, &indices).unwrap();
    let mut out = raps::Parameterization::new().unwrap();
    let error = raps::parameterize_into(&mesh, None, &mut out).unwrap_err();
    assert_eq!(error.status(), Status::INDEX_OUT_OF_RANGE);
    assert!(error.message().contains("12"), "{}", error);
    // A failed run leaves the result empty, and reading it is an error, not garbage.
    assert_eq!(out.vertex_count(), 0);
    assert_eq!(out.uvs().unwrap_err().status(), Status::INVALID_OPERATION);
    assert_eq!(out.stats().unwrap_err().status(), Status::INVALID_OPERATION);
    assert_eq!(
        out.indices().unwrap_err().status(),
        Status::INVALID_OPERATION
    );
    assert_eq!(
        out.chart_ids().unwrap_err().status(),
        Status::INVALID_OPERATION
    );
}

#[test]
fn setter_errors_carry_the_handle_message_and_change_nothing() {
    let mut mesh = raps::Mesh::new().unwrap();
    let error = mesh.set_indices_u32(&[0, 1, 2, 3]).unwrap_err();
    assert_eq!(error.status(), Status::INDEX_COUNT);
    assert!(!error.message().is_empty());
    let error = mesh.set_positions_f32(&[0.0, f32::NAN, 0.0]).unwrap_err();
    assert_eq!(error.status(), Status::NON_FINITE_POSITION);
    assert_eq!(mesh.vertex_count(), 0);
    assert_eq!(
        mesh.set_positions_f32(&[0.0, 1.0]).unwrap_err().status(),
        Status::INVALID_ARGUMENT
    );
    assert_eq!(
        mesh.set_positions_f32_strided(&[0.0; 6], 2)
            .unwrap_err()
            .status(),
        Status::INVALID_ARGUMENT
    );
    assert_eq!(
        raps::parameterize(&mesh, None).unwrap_err().status(),
        Status::EMPTY_MESH
    );

    let mut settings = Settings::new().unwrap();
    settings.set_alpha(2.0).unwrap();
    let error = settings.set_alpha(-1.0).unwrap_err();
    assert_eq!(error.status(), Status::INVALID_ARGUMENT);
    assert!(error.message().contains("alpha"), "{}", error);
    assert_eq!(settings.alpha().unwrap(), 2.0);
    assert!(settings.set_iterations(0).is_err());
    assert_eq!(settings.iterations().unwrap(), 1);
    assert!(settings.set_int(Param(999), 1).is_err());
    assert!(settings.int(Param::ALPHA).is_err()); // alpha is a float
}

#[test]
fn settings_round_trip_and_clone_independently() {
    let mut settings = Settings::new().unwrap();
    settings
        .set_weights(Weights::UNIFORM)
        .unwrap()
        .set_monitor(Monitor::ANGLE)
        .unwrap()
        .set_iterations(3)
        .unwrap()
        .set_iteration_mode(IterationMode::REAPPLY)
        .unwrap()
        .set_boundary(Boundary::SQUARE)
        .unwrap()
        .set_max_triangles(1000)
        .unwrap()
        .set_max_memory_mb(64)
        .unwrap()
        .set_domain(Domain::DISK)
        .unwrap();
    let copy = settings.try_clone().unwrap();
    settings.set_iterations(7).unwrap();
    assert_eq!(copy.iterations().unwrap(), 3);
    assert_eq!(copy.weights().unwrap(), Weights::UNIFORM);
    assert_eq!(copy.monitor().unwrap(), Monitor::ANGLE);
    assert_eq!(copy.iteration_mode().unwrap(), IterationMode::REAPPLY);
    assert_eq!(copy.boundary().unwrap(), Boundary::SQUARE);
    assert_eq!(copy.max_triangles().unwrap(), 1000);
    assert_eq!(copy.max_memory_mb().unwrap(), 64);
    assert_eq!(copy.domain().unwrap(), Domain::DISK);
    let info = Settings::param_info(Param::ALPHA).unwrap();
    assert_eq!(
        (info.name, info.is_float, info.default),
        ("alpha", true, 1.0)
    );
    assert!(Settings::param_info(Param(999)).is_err());
    assert_eq!(format!("{:?}", Monitor::ANGLE), "Monitor::ANGLE");
    assert_eq!(format!("{:?}", Monitor(42)), "Monitor(42)");
    assert!(format!("{:?}", copy).contains("iterations: 3"));
}

#[test]
fn handles_are_freed_exactly_once() {
    // Ownership makes a double free unrepresentable; dropping many handles, including ones that
    // failed half-way, must neither crash nor leak (the sanitizer builds of the C tests cover
    // the library side).
    for _ in 0..2000 {
        let mesh = raps::Mesh::from_f32(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], &[0, 1, 2]);
        let settings = Settings::new().unwrap().try_clone().unwrap();
        drop((mesh, settings));
        let _ = raps::Mesh::from_f32(&[0.0, 0.0], &[0, 1, 2]).unwrap_err();
    }
}

#[test]
fn thread_safety_is_declared_as_the_header_documents() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<raps::Mesh>();
    send_sync::<raps::Settings>();
    send_sync::<raps::Parameterization>();
    send_sync::<raps::Error>();
}

#[test]
fn version_matches_the_header() {
    let (major, minor, patch) = raps::version();
    assert_eq!(major, raps::sys::RAPS_VERSION_MAJOR);
    assert_eq!(
        raps::version_string(),
        format!("{}.{}.{}", major, minor, patch)
    );
}
