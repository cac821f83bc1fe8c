# Sourced by the scripts that walk the SNEE paper grid (docs/results.md): sets grid_scenes to
# its 18 built-in scenes, {sphere,bunny}-{directional,cone,env}-{r0.2,r0.04,smooth}, in the
# order every table lists them.
grid_scenes=()
for object in sphere bunny; do
  for light in directional cone env; do
    for surface in r0.2 r0.04 smooth; do
      grid_scenes+=("$object-$light-$surface")
    done
  done
done
