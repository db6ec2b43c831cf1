//! Several meshes in one atlas (parameterize_scene): each mesh's share reads as its own result,
//! one texel density holds across them, pages never exceed the maximum, bad transforms are
//! refused.
use raps::{Domain, Mesh, Param, Phase, Rotation, Settings, Status};

/// A hexagonal cap: one vertex raised above the middle of six on the unit circle.
fn cap() -> (Vec<f64>, Vec<u32>) {
    let mut xyz = vec![0.0, 0.0, 0.5];
    for k in 0..6 {
        let angle = k as f64 * std::f64::consts::PI / 3.0;
        xyz.extend_from_slice(&[angle.cos(), angle.sin(), 0.0]);
    }
    let indices = (0..6u32)
        .flat_map(|k| [0, 1 + k, 1 + (k + 1) % 6])
        .collect();
    (xyz, indices)
}

fn two_caps() -> (Mesh, Mesh, Vec<u32>) {
    let (xyz, indices) = cap();
    let small = Mesh::from_f64(&xyz, &indices).unwrap();
    let mut big = Mesh::from_f64(&xyz, &indices).unwrap();
    big.set_transform(Some(&[
        2.0, 0.0, 0.0, 4.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0,
    ]))
    .unwrap();
    (small, big, indices)
}

fn atlas_settings() -> Settings {
    let mut settings = Settings::new().unwrap();
    settings.set_domain(Domain::ATLAS).unwrap();
    settings
}

#[test]
fn each_mesh_reads_as_its_own_result_at_one_density() {
    let (small, big, indices) = two_caps();
    let result = raps::parameterize_scene(&[&small, &big], &atlas_settings()).unwrap();
    assert_eq!(result.mesh_count(), 2);
    let remap = result.vertex_remap().unwrap();
    let all = result.indices().unwrap();
    let mut next_vertex = 0;
    for mesh in 0..2 {
        let range = result.mesh_range(mesh).unwrap();
        assert_eq!(range.first_vertex, next_vertex);
        assert_eq!(range.index_count as usize, indices.len());
        let own =
            &all[range.first_index as usize..(range.first_index + range.index_count) as usize];
        for (corner, &input) in own.iter().zip(&indices) {
            assert_eq!(remap[(range.first_vertex + *corner as u64) as usize], input);
        }
        next_vertex += range.vertex_count;
    }
    assert_eq!(next_vertex as usize, result.vertex_count());
    let charts = result.charts().unwrap();
    let texels = |mesh: u32| -> f64 {
        charts
            .iter()
            .filter(|c| c.mesh == mesh)
            .map(|c| c.area_texels)
            .sum()
    };
    assert!((texels(1) / texels(0) / 4.0 - 1.0).abs() < 0.02); // scaled by 2
    assert_eq!(
        result.mesh_range(2).unwrap_err().status(),
        Status::INVALID_ARGUMENT
    );
}

#[test]
fn pages_at_a_density_never_exceed_the_maximum() {
    let (small, big, _) = two_caps();
    let mut settings = atlas_settings();
    settings
        .set_float(Param::ATLAS_TEXELS_PER_UNIT, 30.0)
        .unwrap()
        .set_int(Param::ATLAS_MAX_WIDTH, 64)
        .unwrap()
        .set_int(Param::ATLAS_MAX_HEIGHT, 64)
        .unwrap()
        .set_int(Param::ATLAS_ROTATION, Rotation::QUARTER.0 as i64)
        .unwrap();
    let result = raps::parameterize_scene(&[&small, &big, &small], &settings).unwrap();
    let stats = result.stats().unwrap();
    assert!(stats.page_count >= 2);
    assert!(stats.atlas_width <= 64 && stats.atlas_height <= 64);
    assert_eq!(stats.texels_per_unit, 30.0);
    for chart in result.charts().unwrap() {
        assert!((chart.page as u64) < stats.page_count);
        assert_eq!(chart.rotation_deg % 90.0, 0.0);
    }
}

#[test]
fn bad_transforms_and_scenes_are_refused() {
    let (mut small, big, _) = two_caps();
    let flat = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    assert_eq!(
        small.set_transform(Some(&flat)).unwrap_err().status(),
        Status::INVALID_TRANSFORM
    );
    let disk = Settings::new().unwrap();
    let error = raps::parameterize_scene(&[&small, &big], &disk).unwrap_err();
    assert_eq!(error.status(), Status::INVALID_ARGUMENT);
    assert!(error.message().contains("RAPS_DOMAIN_ATLAS"));
    let error = raps::parameterize_scene(&[], &atlas_settings()).unwrap_err();
    assert_eq!(error.status(), Status::EMPTY_MESH);
}

#[test]
fn groups_and_seam_edges_split_charts_and_bad_ones_are_refused() {
    let (xyz, indices) = cap();
    let mut mesh = Mesh::from_f64(&xyz, &indices).unwrap();
    let settings = atlas_settings();
    let charts =
        |mesh: &Mesh| raps::parameterize(mesh, Some(&settings)).map(|r| r.chart_ids().unwrap());
    assert!(charts(&mesh).unwrap().iter().all(|&c| c == 0));
    mesh.set_triangle_groups(&[0, 0, 0, 1, 1, 1]).unwrap();
    let ids = charts(&mesh).unwrap();
    assert!(ids[..3].iter().all(|c| !ids[3..].contains(c)));
    mesh.set_triangle_groups(&[0, 1]).unwrap();
    assert_eq!(charts(&mesh).unwrap_err().status(), Status::GROUP_COUNT);
    mesh.set_triangle_groups(&[]).unwrap();
    // Polygons reach the library (what they do is the C suite's test_atlas_polygons).
    mesh.set_triangle_polygons(&[0, 0, 1, 1, 2, 2]).unwrap();
    assert_eq!(charts(&mesh).unwrap().len(), 6);
    mesh.set_triangle_polygons(&[0, 1]).unwrap();
    assert_eq!(charts(&mesh).unwrap_err().status(), Status::GROUP_COUNT);
    mesh.set_triangle_polygons(&[]).unwrap();
    mesh.set_seam_edges(&[[0, 1], [4, 0]]).unwrap(); // rim to rim through the apex
    let ids = charts(&mesh).unwrap();
    assert!(ids[..3].iter().all(|c| !ids[3..].contains(c)));
    mesh.set_seam_edges(&[[1, 3]]).unwrap();
    let error = charts(&mesh).unwrap_err();
    assert_eq!(error.status(), Status::SEAM_NOT_AN_EDGE);
    assert!(error.message().contains("seam edge 0 (1, 3)"));
    mesh.set_seam_edges(&[[0, 9]]).unwrap();
    assert_eq!(
        charts(&mesh).unwrap_err().status(),
        Status::INDEX_OUT_OF_RANGE
    );
}

#[test]
fn a_repeated_mesh_shares_its_originals_texels() {
    let (xyz, indices) = cap();
    let original = Mesh::from_f64(&xyz, &indices).unwrap();
    let mut copy = Mesh::from_f64(&xyz, &indices).unwrap();
    copy.set_transform(Some(&[
        0.0, -1.0, 0.0, 4.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
    ]))
    .unwrap();
    let mut settings = atlas_settings();
    settings.set_atlas_stack(raps::Stacking::RIGID).unwrap();
    assert_eq!(settings.atlas_stack().unwrap(), raps::Stacking::RIGID);
    let scene = raps::parameterize_scene(&[&original, &copy], &settings).unwrap();
    let charts = scene.charts().unwrap();
    for (index, chart) in charts.iter().enumerate() {
        let stacked = chart.flags & (raps::sys::RAPS_CHART_STACKED as u32) != 0;
        assert_eq!(stacked, chart.mesh == 1);
        assert_eq!(chart.stacked_on as usize != index, stacked);
    }
    let uv = scene.uvs_f64().unwrap();
    let indices = scene.indices().unwrap();
    let first = scene.mesh_range(0).unwrap();
    let second = scene.mesh_range(1).unwrap();
    for corner in 0..18 {
        let own = uv[first.first_vertex as usize + indices[corner] as usize];
        let copied = uv[second.first_vertex as usize + indices[18 + corner] as usize];
        assert_eq!(own, copied);
    }
}

#[test]
fn a_progress_state_follows_and_cancels_a_scene() {
    let (small, big, _) = two_caps();
    let settings = atlas_settings();
    let progress = raps::ProgressState::new().unwrap();
    raps::parameterize_scene_with_state(&[&small, &big], &settings, &progress).unwrap();
    let done = progress.read();
    assert_eq!((done.phase, done.fraction), (Some(Phase::METRICS), 1.0));
    progress.reset();
    progress.cancel();
    let error =
        raps::parameterize_scene_with_state(&[&small, &big], &settings, &progress).unwrap_err();
    assert_eq!(error.status(), Status::CANCELLED);
    assert_eq!(progress.read().reports, 1);
    // The state was on a private copy: the settings themselves run without it.
    raps::parameterize_scene(&[&small, &big], &settings).unwrap();
    assert_eq!(progress.read().reports, 1);
}
