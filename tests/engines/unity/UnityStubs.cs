// Stand-ins for the few UnityEngine / UnityEditor types probes/unity/PrtProbeImporter.cs uses, so that
// the importer itself compiles with Debian's mono-mcs and runs (tests/engines/unity/RunImporter.cs).
// They hold data only; JsonUtility.FromJson fills public fields by reflection as Unity's does (objects,
// arrays, numbers, booleans, strings; unknown keys ignored).
using System;
using System.Collections.Generic;
using System.Globalization;
using System.Reflection;
using System.Text;

namespace UnityEngine
{
    public class Object { }

    public struct Vector3
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static float Distance(Vector3 a, Vector3 b)
        {
            float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
            return (float)Math.Sqrt(dx * dx + dy * dy + dz * dz);
        }
    }

    public struct SphericalHarmonicsL2
    {
        float[] values;
        public float this[int rgb, int coefficient]
        {
            get { return values == null ? 0f : values[rgb * 9 + coefficient]; }
            set { if (values == null) values = new float[27]; values[rgb * 9 + coefficient] = value; }
        }
    }

    public class LightProbes : Object
    {
        public Vector3[] positions = new Vector3[0];
        public SphericalHarmonicsL2[] bakedProbes = new SphericalHarmonicsL2[0];
        public int count { get { return positions.Length; } }
    }

    public static class LightmapSettings { public static LightProbes lightProbes; }

    public static class Debug { public static void Log(object message) { Console.WriteLine(message); } }

    public static class JsonUtility
    {
        public static T FromJson<T>(string json) { return (T)Json.Convert(Json.Parse(json), typeof(T)); }
    }

    /// A small JSON reader: objects become Dictionary<string, object>, arrays List<object>, numbers double.
    public static class Json
    {
        public static object Parse(string text) { int at = 0; object v = Value(text, ref at); return v; }

        static void Skip(string s, ref int at) { while (at < s.Length && char.IsWhiteSpace(s[at])) at++; }

        static object Value(string s, ref int at)
        {
            Skip(s, ref at);
            char c = s[at];
            if (c == '{')
            {
                var obj = new Dictionary<string, object>();
                at++;
                for (Skip(s, ref at); s[at] != '}'; Skip(s, ref at))
                {
                    string key = (string)Value(s, ref at);
                    Skip(s, ref at); at++;  // ':'
                    obj[key] = Value(s, ref at);
                    Skip(s, ref at);
                    if (s[at] == ',') at++;
                }
                at++;
                return obj;
            }
            if (c == '[')
            {
                var list = new List<object>();
                at++;
                for (Skip(s, ref at); s[at] != ']'; Skip(s, ref at))
                {
                    list.Add(Value(s, ref at));
                    Skip(s, ref at);
                    if (s[at] == ',') at++;
                }
                at++;
                return list;
            }
            if (c == '"')
            {
                var sb = new StringBuilder();
                for (at++; s[at] != '"'; at++)
                {
                    if (s[at] == '\\') { at++; sb.Append(s[at] == 'n' ? '\n' : s[at]); } else sb.Append(s[at]);
                }
                at++;
                return sb.ToString();
            }
            if (s.Substring(at).StartsWith("true")) { at += 4; return true; }
            if (s.Substring(at).StartsWith("false")) { at += 5; return false; }
            if (s.Substring(at).StartsWith("null")) { at += 4; return null; }
            int start = at;
            while (at < s.Length && "+-0123456789.eE".IndexOf(s[at]) >= 0) at++;
            return double.Parse(s.Substring(start, at - start), CultureInfo.InvariantCulture);
        }

        public static object Convert(object v, Type t)
        {
            if (v == null) return null;
            if (t == typeof(int)) return (int)(double)v;
            if (t == typeof(float)) return (float)(double)v;
            if (t == typeof(double)) return (double)v;
            if (t == typeof(bool)) return (bool)v;
            if (t == typeof(string)) return (string)v;
            if (t.IsArray)
            {
                var list = (List<object>)v;
                Array a = Array.CreateInstance(t.GetElementType(), list.Count);
                for (int i = 0; i < list.Count; i++) a.SetValue(Convert(list[i], t.GetElementType()), i);
                return a;
            }
            var dict = (Dictionary<string, object>)v;
            object o = Activator.CreateInstance(t, true);
            foreach (FieldInfo f in t.GetFields(BindingFlags.Public | BindingFlags.Instance))
                if (dict.ContainsKey(f.Name)) f.SetValue(o, Convert(dict[f.Name], f.FieldType));
            return o;
        }
    }
}

namespace UnityEngine.Rendering { }

namespace UnityEngine.SceneManagement
{
    public struct Scene { }
}

namespace UnityEditor
{
    [AttributeUsage(AttributeTargets.Method)]
    public class MenuItem : Attribute { public MenuItem(string path) { } }

    public static class EditorUtility
    {
        public static string OpenFilePanel(string title, string directory, string extension) { return ""; }
        public static void SetDirty(UnityEngine.Object target) { Dirty++; }
        public static int Dirty;
    }
}

namespace UnityEditor.SceneManagement
{
    public static class EditorSceneManager
    {
        public static UnityEngine.SceneManagement.Scene GetActiveScene() { return new UnityEngine.SceneManagement.Scene(); }
        public static bool MarkSceneDirty(UnityEngine.SceneManagement.Scene scene) { return true; }
    }
}
