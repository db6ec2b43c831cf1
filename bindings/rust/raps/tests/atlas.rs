//! The atlas domain on bunny.off, a closed mesh the disk domain refuses.
mod common;

use std::sync::atomic::{AtomicUsize, Ordering};

use raps::{Domain, Param, Parameterization, Phase, Settings, Status};

fn bunny() -> (Vec<f64>, Vec<u32>, raps::Mesh) {
    let (xyz, indices) = common::read_off("meshes/bunny.off");
    let mesh = raps::Mesh::from_f64(&xyz, &indices).expect("bunny is a valid mesh");
    (xyz, indices, mesh)
}

fn atlas_settings(threads: u32) -> Settings {
    let mut settings = Settings::new().unwrap();
    settings
        .set_domain(Domain::ATLAS)
        .unwrap()
        .set_threads(threads)
        .unwrap();
    assert_eq!(settings.domain().unwrap(), Domain::ATLAS);
    assert_eq!(settings.threads().unwrap(), threads);
    settings
}

fn atlas(mesh: &raps::Mesh, threads: u32) -> Parameterization {
    raps::parameterize(mesh, Some(&atlas_settings(threads))).unwrap()
}

/// The phases of progress calls in the order entered, each once: a phase entered twice, or
/// two phases' calls interleaved, show up as a repeat.
fn phase_sequence(calls: &[(Phase, f64)]) -> Vec<Phase> {
    let mut sequence: Vec<Phase> = calls.iter().map(|c| c.0).collect();
    sequence.dedup();
    sequence
}

#[test]
fn a_closed_mesh_becomes_a_valid_atlas() {
    let (xyz, indices, mesh) = bunny();
    let error = raps::parameterize(&mesh, None).unwrap_err();
    assert_eq!(error.status(), Status::NO_BOUNDARY); // the disk domain needs a boundary
    let map = atlas(&mesh, 1);
    let stats = map.stats().unwrap();
    let uvs = map.uvs().unwrap();
    let out = map.indices().unwrap();
    let remap = map.vertex_remap().unwrap();
    let charts = map.chart_ids().unwrap();
    // The input triangles, in input order, over vertices duplicated along seams.
    assert_eq!(out.len(), indices.len());
    assert_eq!(stats.triangle_count as usize, indices.len() / 3);
    assert_eq!(remap.len(), uvs.len());
    assert_eq!(stats.vertex_count as usize, uvs.len());
    assert!(uvs.len() >= xyz.len() / 3);
    assert!(remap.iter().all(|&r| (r as usize) < xyz.len() / 3));
    for (corner, (&o, &i)) in out.iter().zip(&indices).enumerate() {
        assert_eq!(
            remap[o as usize], i,
            "corner {} remaps to its input vertex",
            corner
        );
    }
    // One chart id per triangle, below the chart count.
    assert_eq!(charts.len(), indices.len() / 3);
    assert!(stats.chart_count >= 1);
    assert!(charts.iter().all(|&c| u64::from(c) < stats.chart_count));
    assert!(uvs
        .iter()
        .all(|uv| uv.iter().all(|&c| (0.0..=1.0).contains(&c))));
    assert_eq!(stats.flipped_triangles, 0);
    assert!(stats.atlas_width > 0 && stats.atlas_height > 0);
    assert!(stats.utilization > 0.0 && stats.utilization <= 1.0);
}

#[test]
fn threads_do_not_change_the_map() {
    let (_, _, mesh) = bunny();
    let (one, two) = (atlas(&mesh, 1), atlas(&mesh, 2));
    assert_eq!(one.uvs_f64().unwrap(), two.uvs_f64().unwrap());
    assert_eq!(one.chart_ids().unwrap(), two.chart_ids().unwrap());
}

#[test]
fn progress_reports_the_atlas_phases_without_overlapping_calls() {
    let (_, _, mesh) = bunny();
    let mut calls = Vec::new();
    let (inside, overlaps) = (AtomicUsize::new(0), AtomicUsize::new(0));
    // Chart progress comes from the worker threads: calls must still never overlap.
    let map = raps::parameterize_with_progress(&mesh, Some(&atlas_settings(2)), |phase, f| {
        if inside.fetch_add(1, Ordering::SeqCst) > 0 {
            overlaps.fetch_add(1, Ordering::SeqCst);
        }
        calls.push((phase, f));
        std::thread::sleep(std::time::Duration::from_millis(1)); // another thread could enter
        inside.fetch_sub(1, Ordering::SeqCst);
        true
    })
    .unwrap();
    assert!(map.phase_ms(Phase::SEGMENT) > 0.0 && map.phase_ms(Phase::PACK) > 0.0);
    assert_eq!(
        phase_sequence(&calls),
        [
            Phase::VALIDATE,
            Phase::TOPOLOGY,
            Phase::SEGMENT,
            Phase::INITIAL_MAP,
            Phase::PACK,
            Phase::METRICS
        ]
    );
    assert_eq!(overlaps.load(Ordering::SeqCst), 0);
    assert!(calls.iter().all(|c| (0.0..=1.0).contains(&c.1)));
}

#[test]
fn a_panic_on_a_worker_thread_is_resumed_on_the_caller() {
    let (_, _, mesh) = bunny();
    let settings = atlas_settings(2);
    let outcome = std::panic::catch_unwind(|| {
        let _ = raps::parameterize_with_progress(&mesh, Some(&settings), |phase, fraction| {
            if phase == Phase::INITIAL_MAP && fraction > 0.0 {
                panic!("stop the charts");
            }
            true
        });
    });
    let payload = outcome.unwrap_err();
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"stop the charts"));
    assert!(raps::parameterize(&mesh, Some(&settings)).is_ok());
}

#[test]
fn atlas_settings_round_trip() {
    // (parameter, name, is_float, min, max, default), as raps_param_info gives them.
    #[rustfmt::skip]
    let expected = [
        (Param::THREADS, "threads", false, 0.0, 1024.0, 0.0),
        (Param::ATLAS_RESOLUTION, "atlas_resolution", false, 16.0, 16384.0, 1024.0),
        (Param::ATLAS_PADDING, "atlas_padding", false, 0.0, 64.0, 1.0),
        (Param::WELD_TOLERANCE, "weld_tolerance", true, 0.0, f64::MAX, 0.0),
        (Param::HARD_EDGE_ANGLE, "hard_edge_angle", true, 0.0, 180.0, 180.0),
        (Param::ATLAS_MAX_L2_STRETCH, "atlas_max_l2_stretch", true, 1.0, 10.0, 1.01),
        (Param::ATLAS_MAX_LINF_STRETCH, "atlas_max_linf_stretch", true, 1.0, 1000.0, 2.9),
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
        // Debug lists the atlas parameters too, past the gap after THREADS.
        assert!(
            format!("{:?}", defaults).contains(&format!("{}: ", name)),
            "{}",
            name
        );
    }

    let mut settings = atlas_settings(2);
    settings
        .set_atlas_resolution(512)
        .unwrap()
        .set_atlas_padding(4)
        .unwrap()
        .set_weld_tolerance(1e-6)
        .unwrap()
        .set_hard_edge_angle(60.0)
        .unwrap()
        .set_atlas_max_l2_stretch(1.5)
        .unwrap()
        .set_atlas_max_linf_stretch(4.0)
        .unwrap();
    let copy = settings.try_clone().unwrap();
    assert_eq!(copy.threads().unwrap(), 2);
    assert_eq!(copy.atlas_resolution().unwrap(), 512);
    assert_eq!(copy.atlas_padding().unwrap(), 4);
    assert_eq!(copy.weld_tolerance().unwrap(), 1e-6);
    assert_eq!(copy.hard_edge_angle().unwrap(), 60.0);
    assert_eq!(copy.atlas_max_l2_stretch().unwrap(), 1.5);
    assert_eq!(copy.atlas_max_linf_stretch().unwrap(), 4.0);
    for error in [
        settings.set_threads(1025).unwrap_err(),
        settings.set_atlas_resolution(8).unwrap_err(),
        settings.set_atlas_padding(65).unwrap_err(),
        settings.set_hard_edge_angle(181.0).unwrap_err(),
        settings.set_atlas_max_l2_stretch(0.5).unwrap_err(),
    ] {
        assert_eq!(error.status(), Status::INVALID_ARGUMENT);
    }
    // A failed setter changes nothing.
    assert_eq!(settings.atlas_resolution().unwrap(), 512);
    assert_eq!(settings.hard_edge_angle().unwrap(), 60.0);
}
