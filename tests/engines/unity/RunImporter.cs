// Runs probes/unity/PrtProbeImporter.cs (compiled with mono-mcs against UnityStubs.cs): a light probe
// group is "baked" at the export's positions (zero coefficients), Import() replaces them from the
// export, and Unity's shader evaluation of the result, ShadeSH9 of UnityCG.cginc (the
// SphericalHarmonicsL2 -> unity_SHAr..SHC packing and SHEvalLinearL0L1 + SHEvalLinearL2, re-implemented
// here: Unity's shaders do not run outside Unity), must give prt's E(n)/pi at the mirrored normal
// (-n.x, n.y, n.z) for every valid probe and test direction, within 1e-4 of the probe's scale; invalid
// probes must keep the baked (zero) values.
// Usage: mono run_importer.exe UNITY_JSON TRUTH_JSON [UNITY_JSON TRUTH_JSON ...]
using System;
using System.Collections.Generic;
using System.IO;
using UnityEngine;

public static class RunImporter
{
    static int passed, failed;

    static void Check(bool ok, string what)
    {
        if (ok) { passed++; return; }
        failed++;
        if (failed <= 20) Console.WriteLine("FAIL " + what);
    }

    static double[] ShadeSH9(SphericalHarmonicsL2 sh, double x, double y, double z)
    {
        var rgb = new double[3];
        for (int c = 0; c < 3; c++)
        {
            Func<int, double> u = i => sh[c, i];
            double[] a = { u(3), u(1), u(2), u(0) - u(6) };        // unity_SHA
            double[] b = { u(4), u(5), 3 * u(6), u(7) };           // unity_SHB
            double l0l1 = a[0] * x + a[1] * y + a[2] * z + a[3];
            double l2 = b[0] * x * y + b[1] * y * z + b[2] * z * z + b[3] * z * x + u(8) * (x * x - y * y);
            rgb[c] = Math.Max(0.0, l0l1 + l2);
        }
        return rgb;
    }

    static void RunOne(string exportPath, string truthPath)
    {
        var export = (Dictionary<string, object>)Json.Parse(File.ReadAllText(exportPath));
        var entries = (List<object>)export["probes"];
        var positions = new Vector3[entries.Count];
        for (int p = 0; p < entries.Count; p++)
        {
            var pos = (List<object>)((Dictionary<string, object>)entries[p])["position"];
            positions[p] = new Vector3((float)(double)pos[0], (float)(double)pos[1], (float)(double)pos[2]);
        }
        LightmapSettings.lightProbes = new LightProbes { positions = positions, bakedProbes = new SphericalHarmonicsL2[positions.Length] };
        int replaced = PrtProbeImporter.Import(exportPath);

        var truth = (Dictionary<string, object>)Json.Parse(File.ReadAllText(truthPath));
        var directions = (List<object>)truth["directions"];
        var probes = (List<object>)truth["probes"];
        int valid = 0;
        for (int p = 0; p < probes.Count; p++)
        {
            var probe = (Dictionary<string, object>)probes[p];
            var position = (List<object>)probe["position"];
            Check(Math.Abs(positions[p].x + (double)position[0]) < 1e-6 && Math.Abs(positions[p].y - (double)position[1]) < 1e-6,
                  exportPath + ": probe " + p + " position is prt's mirrored in x");
            var sh = LightmapSettings.lightProbes.bakedProbes[p];
            if (!(bool)probe["valid"])
            {
                Check(sh[0, 0] == 0f, exportPath + ": invalid probe " + p + " keeps the baked value");
                continue;
            }
            valid++;
            var want = (List<object>)probe["e_over_pi"];
            double scale = 1e-12;
            foreach (List<object> w in want) foreach (object v in w) scale = Math.Max(scale, Math.Abs((double)v));
            for (int k = 0; k < directions.Count; k++)
            {
                var d = (List<object>)directions[k];
                double[] got = ShadeSH9(sh, -(double)d[0], (double)d[1], (double)d[2]);
                var e = (List<object>)want[k];
                for (int c = 0; c < 3; c++)
                {
                    double expected = Math.Max(0.0, (double)e[c]);
                    Check(Math.Abs(got[c] - expected) <= 1e-4 * scale,
                          exportPath + ": probe " + p + " direction " + k + " channel " + c + ": Unity " + got[c] + ", prt " + expected);
                }
            }
        }
        Check(replaced == valid, exportPath + ": Import replaced " + replaced + " probes, expected the " + valid + " valid ones");
    }

    public static int Main(string[] args)
    {
        for (int i = 0; i + 1 < args.Length; i += 2) RunOne(args[i], args[i + 1]);
        Console.WriteLine("engines_unity: " + passed + " passed, " + failed + " failed");
        return failed == 0 && passed > 0 ? 0 : 1;
    }
}
