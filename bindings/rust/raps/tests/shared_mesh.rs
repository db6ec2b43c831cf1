//! The Rust binding on a real shared mesh (camelhead.off, a disk-shaped scan).
mod common;

use raps::{Monitor, Parameterization, Phase, Settings, Status};

fn camelhead() -> (Vec<f64>, Vec<u32>, raps::Mesh) {
    let (xyz, indices) = common::read_off("meshes/camelhead.off");
    let mesh = raps::Mesh::from_f64(&xyz, &indices).expect("camelhead is a valid mesh");
    (xyz, indices, mesh)
}

fn signed_area(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> f32 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

#[test]
fn area_monitor_is_valid_and_less_distorted_than_none() {
    let (xyz, indices, mesh) = camelhead();
    assert_eq!(mesh.vertex_count(), xyz.len() / 3);
    assert_eq!(mesh.triangle_count(), indices.len() / 3);
    let mut plain = Settings::new().unwrap();
    plain.set_monitor(Monitor::NONE).unwrap();
    let adaptive = Settings::new().unwrap();
    assert_eq!(adaptive.monitor().unwrap(), Monitor::AREA); // the default

    let first = raps::parameterize(&mesh, Some(&plain)).unwrap();
    let second = raps::parameterize(&mesh, Some(&adaptive)).unwrap();
    for map in [&first, &second] {
        let stats = map.stats().unwrap();
        assert_eq!(stats.flipped_triangles, 0);
        assert_eq!(stats.vertex_count as usize, xyz.len() / 3);
        let uvs = map.uvs().unwrap();
        assert_eq!(uvs.len(), xyz.len() / 3);
        assert!(uvs
            .iter()
            .all(|uv| uv.iter().all(|&c| (0.0..=1.0).contains(&c))));
        for t in indices.chunks(3).step_by(97) {
            let area = signed_area(uvs[t[0] as usize], uvs[t[1] as usize], uvs[t[2] as usize]);
            assert!(
                area > 0.0,
                "counter-clockwise in 3D stays counter-clockwise in uv"
            );
        }
        assert_eq!(map.indices().unwrap(), indices);
        let identity: Vec<u32> = (0..uvs.len() as u32).collect();
        assert_eq!(map.vertex_remap().unwrap(), identity);
    }
    assert_eq!(first.stats().unwrap().adaptive_solves, 0);
    assert_eq!(second.stats().unwrap().adaptive_solves, 1);
    // The adaptive step equidistributes area: docs/bench-method.md measures 2.509 -> 0.721.
    let (before, after) = (
        first.stats().unwrap().area_log_mean,
        second.stats().unwrap().area_log_mean,
    );
    assert!(
        after < 0.5 * before,
        "area mean |log r| {} -> {}",
        before,
        after
    );
    assert!(second.phase_ms(Phase::ADAPT) > 0.0);
    // The fields appended for the atlas, as the disk domain fills them.
    let stats = second.stats().unwrap();
    assert_eq!(
        (stats.chart_count, stats.atlas_width, stats.atlas_height),
        (1, 0, 0)
    );
    assert!(stats.utilization > 0.0 && stats.utilization <= 1.0);
    let charts = second.chart_ids().unwrap();
    assert_eq!(charts.len(), indices.len() / 3);
    assert!(charts.iter().all(|&c| c == 0));
}

#[test]
fn input_precisions_strides_and_index_widths_agree() {
    let (xyz, indices, mesh) = camelhead();
    let reference = raps::parameterize(&mesh, None).unwrap();
    let f64_uvs = reference.uvs_f64().unwrap();
    for (single, double) in reference.uvs().unwrap().iter().zip(&f64_uvs) {
        assert!((single[0] as f64 - double[0]).abs() < 1e-6);
        assert!((single[1] as f64 - double[1]).abs() < 1e-6);
    }
    // f32 positions in an interleaved (position, normal) buffer, u16 indices.
    let mut interleaved = Vec::new();
    for p in xyz.chunks(3) {
        interleaved.extend(p.iter().map(|&c| c as f32));
        interleaved.extend_from_slice(&[0.0, 0.0, 1.0]);
    }
    let packed: Vec<f32> = xyz.iter().map(|&c| c as f32).collect();
    let short: Vec<u16> = indices.iter().map(|&i| i as u16).collect();
    let mut strided = raps::Mesh::new().unwrap();
    strided.set_positions_f32_strided(&interleaved, 6).unwrap();
    strided.set_indices_u16(&short).unwrap();
    let plain = raps::Mesh::from_f32(&packed, &indices).unwrap();
    let a = raps::parameterize(&strided, None)
        .unwrap()
        .uvs_f64()
        .unwrap();
    let b = raps::parameterize(&plain, None).unwrap().uvs_f64().unwrap();
    assert_eq!(a, b);
    assert_eq!(strided.vertex_count(), xyz.len() / 3);
}

#[test]
fn concurrent_runs_share_mesh_and_settings() {
    let (_, _, mesh) = camelhead();
    let mut settings = Settings::new().unwrap();
    settings.set_iterations(2).unwrap();
    let expected = raps::parameterize(&mesh, Some(&settings))
        .unwrap()
        .uvs_f64()
        .unwrap();
    let (mesh, settings) = (&mesh, &settings);
    std::thread::scope(|scope| {
        let runs: Vec<_> = (0..4)
            .map(|_| scope.spawn(move || raps::parameterize(mesh, Some(settings)).unwrap()))
            .collect();
        for run in runs {
            // A Parameterization is Send: it comes back from its thread.
            let map: Parameterization = run.join().unwrap();
            assert_eq!(map.uvs_f64().unwrap(), expected);
        }
    });
}

#[test]
fn progress_reports_the_disk_phases_in_order() {
    let (_, _, mesh) = camelhead();
    let mut calls = Vec::new();
    raps::parameterize_with_progress(&mesh, None, |phase, fraction| {
        calls.push((phase, fraction));
        true
    })
    .unwrap();
    // Each phase entered once, in this order; SEGMENT and PACK are the atlas's.
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
    assert!(phases.iter().all(|p| Phase::all().any(|q| q == *p)));
    assert!(calls.iter().all(|c| (0.0..=1.0).contains(&c.1)));
}

#[test]
fn cancelling_fails_and_leaves_everything_usable() {
    let (_, _, mesh) = camelhead();
    let settings = Settings::new().unwrap();
    let error =
        raps::parameterize_with_progress(&mesh, Some(&settings), |phase, _| phase < Phase::ADAPT)
            .unwrap_err();
    assert_eq!(error.status(), Status::CANCELLED);
    // The callback lived on a private copy: the shared settings run without it.
    let map = raps::parameterize(&mesh, Some(&settings)).unwrap();
    assert_eq!(map.vertex_count(), mesh.vertex_count());
}

#[test]
fn a_panic_in_progress_is_resumed_after_the_run() {
    let (_, _, mesh) = camelhead();
    let outcome = std::panic::catch_unwind(|| {
        let _ = raps::parameterize_with_progress(&mesh, None, |_, _| panic!("stop here"));
    });
    let payload = outcome.unwrap_err();
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"stop here"));
    // The mesh is still fine.
    assert!(raps::parameterize(&mesh, None).is_ok());
}

#[test]
fn a_progress_state_is_polled_and_cancelled_from_another_thread() {
    let (_, _, mesh) = camelhead();
    let progress = raps::ProgressState::new().unwrap();
    let before = progress.read();
    assert_eq!((before.phase, before.reports), (None, 0));

    // A cancel before the run stops it at its first report, and stays until reset.
    progress.cancel();
    let error = raps::parameterize_with_state(&mesh, None, &progress).unwrap_err();
    assert_eq!(error.status(), Status::CANCELLED);
    assert_eq!(progress.read().reports, 1);
    progress.reset();
    raps::parameterize_with_state(&mesh, None, &progress).unwrap();
    let done = progress.read();
    assert_eq!((done.phase, done.fraction), (Some(Phase::METRICS), 1.0));
    assert!(done.reports > 5, "{} reports", done.reports);

    // Another thread polls the state and cancels once the run adapts.
    progress.reset();
    let mut settings = Settings::new().unwrap();
    settings.set_iterations(100).unwrap();
    let outcome = std::thread::scope(|scope| {
        let poller = scope.spawn(|| {
            let start = std::time::Instant::now();
            while start.elapsed().as_secs() < 60 {
                if progress.read().phase == Some(Phase::ADAPT) {
                    progress.cancel();
                    return true;
                }
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            false
        });
        let outcome = raps::parameterize_with_state(&mesh, Some(&settings), &progress);
        assert!(poller.join().unwrap(), "the poller saw ADAPT");
        outcome
    });
    assert_eq!(outcome.unwrap_err().status(), Status::CANCELLED);
    assert_eq!(progress.read().phase, Some(Phase::ADAPT));
}
