@tool
extends EditorScript
## Replaces the probe SH of a baked LightmapGI with a prt export (prt probes ... --format godot).
## See README.md in this folder. Godot 4.x.
##
## Godot stores probe lighting in LightmapGIData.probe_data: "points" (PackedVector3Array), "sh"
## (PackedColorArray, 9 Colors per point), "tetrahedra", "bsp", "bounds", "interior", "baked_exposure"
## (scene/3d/lightmap_gi.cpp, LightmapGIData::_set_probe_data / _get_probe_data). This script keeps
## Godot's points, tetrahedra and BSP and overwrites "sh" of every point that matches an exported valid
## probe (within TOLERANCE), so bake the LightmapGI with LightmapProbe nodes at the export's positions.
##
## Use: open the scene, set JSON_PATH and LIGHTMAP_PATH below, then File > Run (Ctrl+Shift+X).

const JSON_PATH := "res://probes.json"
const LIGHTMAP_PATH := "LightmapGI"  # node path from the edited scene's root
const TOLERANCE := 1e-3


func _run() -> void:
	var root := get_editor_interface().get_edited_scene_root()
	var lightmap := root.get_node(LIGHTMAP_PATH) as LightmapGI
	if lightmap == null or lightmap.light_data == null:
		push_error("prt: no baked LightmapGI at %s" % LIGHTMAP_PATH)
		return
	var text := FileAccess.get_file_as_string(JSON_PATH)
	var doc = JSON.parse_string(text)
	if typeof(doc) != TYPE_DICTIONARY or doc.get("format", "") != "prt-probes-godot":
		push_error("prt: %s is not a prt Godot probe export" % JSON_PATH)
		return
	var replaced := apply_probes(lightmap.light_data, doc["probes"])
	ResourceSaver.save(lightmap.light_data)
	print("prt: replaced the SH of %d probe points from %s" % [replaced, JSON_PATH])


## Overwrites probe_data["sh"] of `data` for the points that match valid exported probes; returns how many.
static func apply_probes(data: LightmapGIData, probes: Array) -> int:
	var probe_data: Dictionary = data.get("probe_data")
	var points: PackedVector3Array = probe_data["points"]
	var sh: PackedColorArray = probe_data["sh"]
	var replaced := 0
	for i in points.size():
		for probe in probes:
			if not probe["valid"]:
				continue
			var p: Array = probe["position"]
			if points[i].distance_to(Vector3(p[0], p[1], p[2])) > TOLERANCE:
				continue
			var values: Array = probe["sh"]  # 27 floats: 9 colours r, g, b
			for k in 9:
				sh[i * 9 + k] = Color(values[3 * k], values[3 * k + 1], values[3 * k + 2])
			replaced += 1
			break
	probe_data["sh"] = sh
	data.set("probe_data", probe_data)
	return replaced
