fn main() -> Result<(), raps::Error> {
    // A hexagonal cap: one vertex raised above the middle of six on a circle.
    let xyz = [
        0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.5, 0.866, 0.0, -0.5, 0.866, 0.0, //
        -1.0, 0.0, 0.0, -0.5, -0.866, 0.0, 0.5, -0.866, 0.0,
    ];
    let indices = [0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 6, 0, 6, 1];
    let mesh = raps::Mesh::from_f32(&xyz, &indices)?;
    let mut settings = raps::Settings::new()?;
    settings.set_monitor(raps::Monitor::AREA)?.set_alpha(1.0)?;
    let map = raps::parameterize(&mesh, Some(&settings))?;
    println!("uv of the top: {:?}", map.uvs()?[0]);
    println!("flipped triangles: {}", map.stats()?.flipped_triangles);

    // Those uvs repacked into an atlas at 64 texels per unit: one (u, v) per triangle corner;
    // each island is only moved, turned and uniformly scaled, never mapped again.
    let uv = map.uvs()?;
    let corners: Vec<f32> = map
        .indices()?
        .iter()
        .flat_map(|&v| uv[v as usize])
        .collect();
    let mut mesh = mesh;
    mesh.set_corner_uvs_f32(&corners)?;
    let mut repack = raps::Settings::new()?;
    repack
        .set_domain(raps::Domain::ATLAS)?
        .set_atlas_repack(true)?;
    repack.set_float(raps::Param::ATLAS_TEXELS_PER_UNIT, 64.0)?;
    let atlas = raps::parameterize(&mesh, Some(&repack))?;
    println!("repacked charts: {}", atlas.stats()?.chart_count);

    // The cap twice in one scene, the copy moved: with stacking the copy costs no texels.
    let mut copy = raps::Mesh::from_f32(&xyz, &indices)?;
    copy.set_transform(Some(&[
        1.0, 0.0, 0.0, 3.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
    ]))?;
    let mut stack = raps::Settings::new()?;
    stack
        .set_domain(raps::Domain::ATLAS)?
        .set_atlas_stack(raps::Stacking::RIGID)?;
    let scene = raps::parameterize_scene(&[&mesh, &copy], &stack)?;
    let stacked_flag = raps::sys::RAPS_CHART_STACKED as u32;
    let stacked = scene
        .charts()?
        .iter()
        .filter(|c| c.flags & stacked_flag != 0)
        .count();
    println!("stacked charts: {}", stacked);
    Ok(())
}
