//! Existing uvs repacked (Settings::set_atlas_repack): the islands of a hexagonal cap's corner
//! uvs come back as charts, each only moved, turned and uniformly scaled, at one density; bad
//! uvs are refused with their own status.
use raps::{Domain, Mesh, Settings, Status};

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

/// Two islands: triangles 0-2 as the cap lies (x, y), triangles 3-5 mirrored and moved.
fn corner_uvs(xyz: &[f64], indices: &[u32]) -> Vec<f64> {
    let mut uv = Vec::new();
    for (corner, &v) in indices.iter().enumerate() {
        let (x, y) = (xyz[3 * v as usize], xyz[3 * v as usize + 1]);
        if corner / 3 < 3 {
            uv.extend_from_slice(&[x, y]);
        } else {
            uv.extend_from_slice(&[5.0 - 2.0 * x, 2.0 * y]);
        }
    }
    uv
}

fn repack_settings() -> Settings {
    let mut settings = Settings::new().unwrap();
    settings
        .set_domain(Domain::ATLAS)
        .unwrap()
        .set_threads(1)
        .unwrap()
        .set_atlas_repack(true)
        .unwrap();
    assert!(settings.atlas_repack().unwrap());
    settings
}

/// (a, b) as complex numbers: a / b.
fn divide(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let d = b[0] * b[0] + b[1] * b[1];
    [
        (a[0] * b[0] + a[1] * b[1]) / d,
        (a[1] * b[0] - a[0] * b[1]) / d,
    ]
}

#[test]
fn islands_keep_their_shape_at_one_density() {
    let (xyz, indices) = cap();
    let mut mesh = Mesh::from_f64(&xyz, &indices).unwrap();
    let uv = corner_uvs(&xyz, &indices);
    mesh.set_corner_uvs_f64(&uv).unwrap();
    let map = raps::parameterize(&mesh, Some(&repack_settings())).unwrap();
    let stats = map.stats().unwrap();
    assert_eq!((stats.chart_count, stats.flipped_triangles), (2, 3));
    let (w, h) = (stats.atlas_width as f64, stats.atlas_height as f64);
    let out: Vec<[f64; 2]> = map
        .uvs_f64()
        .unwrap()
        .iter()
        .map(|p| [p[0] * w, p[1] * h])
        .collect();
    let out_indices = map.indices().unwrap();
    let ids = map.chart_ids().unwrap();
    for chart in 0..2u32 {
        // Corners of the chart: (input uv, output texel).
        let pairs: Vec<([f64; 2], [f64; 2])> = (0..18)
            .filter(|&c| ids[c / 3] == chart)
            .map(|c| ([uv[2 * c], uv[2 * c + 1]], out[out_indices[c] as usize]))
            .collect();
        let (a0, b0) = pairs[0];
        let far = pairs
            .iter()
            .max_by(|p, q| {
                let dp = (p.0[0] - a0[0]).hypot(p.0[1] - a0[1]);
                let dq = (q.0[0] - a0[0]).hypot(q.0[1] - a0[1]);
                dp.partial_cmp(&dq).unwrap()
            })
            .unwrap();
        let z = divide(
            [far.1[0] - b0[0], far.1[1] - b0[1]],
            [far.0[0] - a0[0], far.0[1] - a0[1]],
        );
        let reach = (far.1[0] - b0[0]).hypot(far.1[1] - b0[1]);
        for (a, b) in &pairs {
            let d = [a[0] - a0[0], a[1] - a0[1]];
            let expected = [
                b0[0] + z[0] * d[0] - z[1] * d[1],
                b0[1] + z[1] * d[0] + z[0] * d[1],
            ];
            assert!((b[0] - expected[0]).hypot(b[1] - expected[1]) < 1e-6 * reach);
        }
    }
    let charts = map.charts().unwrap();
    let density: Vec<f64> = charts.iter().map(|c| c.area_texels / c.area_3d).collect();
    assert!((density[0] / density[1] - 1.0).abs() < 1e-6);
}

#[test]
fn bad_uvs_are_refused() {
    let (xyz, indices) = cap();
    let mut mesh = Mesh::from_f64(&xyz, &indices).unwrap();
    let settings = repack_settings();
    let run = |mesh: &Mesh| raps::parameterize(mesh, Some(&settings)).map(|_| ());
    assert_eq!(run(&mesh).unwrap_err().status(), Status::UV_COUNT);
    let mut uv: Vec<f32> = corner_uvs(&xyz, &indices)
        .iter()
        .map(|&x| x as f32)
        .collect();
    mesh.set_corner_uvs_f32(&uv[..12]).unwrap();
    assert_eq!(run(&mesh).unwrap_err().status(), Status::UV_COUNT);
    uv[9] = f32::NAN;
    let error = mesh.set_corner_uvs_f32(&uv).unwrap_err();
    assert_eq!(error.status(), Status::NON_FINITE_UV);
    assert!(error.message().contains("corner 4"));
    assert_eq!(
        mesh.set_corner_uvs_f32(&uv[..3]).unwrap_err().status(),
        Status::INVALID_ARGUMENT
    );
    mesh.set_corner_uvs_f64(&[0.5; 36]).unwrap(); // every island a point
    assert_eq!(
        run(&mesh).unwrap_err().status(),
        Status::DEGENERATE_UV_CHART
    );
    mesh.set_corner_uvs_f64(&[]).unwrap();
    assert_eq!(run(&mesh).unwrap_err().status(), Status::UV_COUNT);
}
