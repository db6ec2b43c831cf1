//! Test support: the shared data folder, an OFF reader and a closed mesh.
#![allow(dead_code)]

use std::path::PathBuf;

/// RAPS_SHARED_DATA_DIR (CTest sets it); missing data fails the test, it never skips it.
pub fn data_file(relative: &str) -> PathBuf {
    let dir = std::env::var("RAPS_SHARED_DATA_DIR")
        .expect("RAPS_SHARED_DATA_DIR must name the shared test data folder");
    let path = PathBuf::from(dir).join(relative);
    assert!(
        path.is_file(),
        "shared test data missing: {}",
        path.display()
    );
    path
}

/// Positions (x, y, z per vertex) and triangle indices of an OFF file, polygons fanned.
pub fn read_off(relative: &str) -> (Vec<f64>, Vec<u32>) {
    let text = std::fs::read_to_string(data_file(relative)).expect("readable OFF file");
    let mut words = text
        .lines()
        .flat_map(|l| l.split('#').next().unwrap().split_whitespace());
    assert_eq!(words.next(), Some("OFF"));
    let mut number = || words.next().expect("truncated OFF file");
    let (nv, nf) = (
        number().parse::<usize>().unwrap(),
        number().parse::<usize>().unwrap(),
    );
    number();
    let xyz: Vec<f64> = (0..3 * nv).map(|_| number().parse().unwrap()).collect();
    let mut indices = Vec::new();
    for _ in 0..nf {
        let n: usize = number().parse().unwrap();
        let face: Vec<u32> = (0..n).map(|_| number().parse().unwrap()).collect();
        for k in 1..n - 1 {
            indices.extend_from_slice(&[face[0], face[k], face[k + 1]]);
        }
    }
    (xyz, indices)
}

/// A closed mesh (no boundary loop), which the disk domain refuses.
pub fn icosahedron() -> (Vec<f64>, Vec<u32>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let xyz = vec![
        -1.0, t, 0.0, 1.0, t, 0.0, -1.0, -t, 0.0, 1.0, -t, 0.0, 0.0, -1.0, t, 0.0, 1.0, t, 0.0,
        -1.0, -t, 0.0, 1.0, -t, t, 0.0, -1.0, t, 0.0, 1.0, -t, 0.0, -1.0, -t, 0.0, 1.0,
    ];
    let indices = vec![
        0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7,
        1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9,
        8, 1,
    ];
    (xyz, indices)
}

/// An open mesh: a hexagonal cap, one vertex raised above the middle of six on a circle.
pub fn fan_disk() -> (Vec<f64>, Vec<u32>) {
    let mut xyz = vec![0.0, 0.0, 0.5];
    let mut indices = Vec::new();
    for k in 0..6u32 {
        let angle = f64::from(k) * std::f64::consts::PI / 3.0;
        xyz.extend_from_slice(&[angle.cos(), angle.sin(), 0.0]);
        indices.extend_from_slice(&[0, 1 + k, 1 + (k + 1) % 6]);
    }
    (xyz, indices)
}
