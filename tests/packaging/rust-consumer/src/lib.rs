//! Parameterizes a square of two triangles through the raps crate (bundled libraps).

#[cfg(test)]
mod tests {
    #[test]
    fn a_square_maps_into_the_unit_square() {
        let xyz = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        let mesh = raps::Mesh::from_f32(&xyz, &[0, 1, 2, 0, 2, 3]).expect("mesh");
        let map = raps::parameterize(&mesh, None).expect("parameterize");
        let uvs = map.uvs().expect("uvs");
        assert_eq!(uvs.len(), 4);
        for uv in uvs {
            assert!(
                (0.0..=1.0).contains(&uv[0]) && (0.0..=1.0).contains(&uv[1]),
                "{:?}",
                uv
            );
        }
        assert_eq!(map.stats().expect("stats").flipped_triangles, 0);
    }
}
