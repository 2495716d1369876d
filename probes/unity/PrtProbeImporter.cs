// Unity editor script: replaces the baked light probe data of the open scene with a prt export
// (prt probes ... --format unity -o probes.json). See README.md in this folder.
//
// Unity cannot take probe positions from outside: bake the scene first with a LightProbeGroup whose
// probes stand at the same positions (the export's "position" values are already in Unity's frame),
// then run Tools > prt > Import Light Probes. Each baked probe is matched to the export's nearest probe
// within a tolerance; matched probes get prt's coefficients, unmatched ones (and the export's invalid
// probes, which lie inside geometry) keep Unity's own. Put this file in an Editor folder.
#if UNITY_EDITOR
using System;
using System.IO;
using UnityEditor;
using UnityEditor.SceneManagement;
using UnityEngine;
using UnityEngine.Rendering;

public static class PrtProbeImporter
{
    [Serializable]
    class ProbeEntry
    {
        public int index;
        public float[] position;  // Unity frame (x mirrored from glTF / prt)
        public bool valid;
        public float[] sh;        // 27 floats: SphericalHarmonicsL2 order sh[channel * 9 + coefficient]
    }

    [Serializable]
    class ProbeFile
    {
        public string format;
        public int version;
        public ProbeEntry[] probes;
    }

    /// Largest distance (scene units) between a baked probe and an exported one that still counts as the same probe.
    public static float matchTolerance = 1e-3f;

    [MenuItem("Tools/prt/Import Light Probes...")]
    static void ImportFromMenu()
    {
        string path = EditorUtility.OpenFilePanel("prt light probes (--format unity)", "", "json");
        if (string.IsNullOrEmpty(path)) return;
        int replaced = Import(path);
        Debug.Log($"prt: replaced {replaced} of {LightmapSettings.lightProbes.count} baked light probes from {path}");
    }

    /// Replaces the matching probes of LightmapSettings.lightProbes.bakedProbes; returns how many.
    public static int Import(string path)
    {
        var file = JsonUtility.FromJson<ProbeFile>(File.ReadAllText(path));
        if (file == null || file.format != "prt-probes-unity" || file.probes == null)
            throw new InvalidDataException($"{path}: not a prt Unity probe export");
        LightProbes lightProbes = LightmapSettings.lightProbes;
        if (lightProbes == null || lightProbes.count == 0)
            throw new InvalidOperationException("the scene has no baked light probes: bake a LightProbeGroup at the export's positions first");

        Vector3[] positions = lightProbes.positions;
        SphericalHarmonicsL2[] baked = lightProbes.bakedProbes;
        int replaced = 0;
        for (int p = 0; p < positions.Length; ++p)
        {
            ProbeEntry best = null;
            float bestDistance = matchTolerance;
            foreach (ProbeEntry e in file.probes)
            {
                float d = Vector3.Distance(positions[p], new Vector3(e.position[0], e.position[1], e.position[2]));
                if (d <= bestDistance) { bestDistance = d; best = e; }
            }
            if (best == null || !best.valid || best.sh == null || best.sh.Length != 27) continue;
            var sh = new SphericalHarmonicsL2();
            for (int channel = 0; channel < 3; ++channel)
                for (int i = 0; i < 9; ++i)
                    sh[channel, i] = best.sh[channel * 9 + i];
            baked[p] = sh;
            ++replaced;
        }
        lightProbes.bakedProbes = baked;
        EditorUtility.SetDirty(lightProbes);
        EditorSceneManager.MarkSceneDirty(EditorSceneManager.GetActiveScene());
        return replaced;
    }
}
#endif
