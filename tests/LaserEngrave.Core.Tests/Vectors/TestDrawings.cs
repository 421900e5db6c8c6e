using System.Globalization;
using System.Text;
using System.Text.Json;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>The committed test drawings with their exact figures (from tools/make-test-drawings.py), and small drawings built in code.</summary>
internal static class TestDrawings
{
    public const double MicrostepUm = 0.09921875;

    public static string Folder
    {
        get
        {
            var dir = new DirectoryInfo(AppContext.BaseDirectory);
            while (dir is not null && !System.IO.File.Exists(Path.Combine(dir.FullName, "LaserEngrave.sln")))
            {
                dir = dir.Parent;
            }

            return dir is null ? throw new InvalidOperationException("LaserEngrave.sln not found") : Path.Combine(dir.FullName, "assets", "drawings");
        }
    }

    public static string File(string name) => Path.Combine(Folder, name);

    /// <summary>expected.json's entry for a drawing: exact length, the curved parts' sum of length / radius, vertices, bounds.</summary>
    public static JsonElement Expected(string name)
    {
        using var json = JsonDocument.Parse(System.IO.File.ReadAllText(File("expected.json")));
        return json.RootElement.GetProperty(name).Clone();
    }

    /// <summary>An ASCII DXF in millimetres ($INSUNITS 4 unless told) with the given BLOCKS and ENTITIES bodies.</summary>
    public static string Dxf(string entities, string blocks = "", int? insUnits = 4)
    {
        var s = new StringBuilder();
        s.Append("0\nSECTION\n2\nHEADER\n");
        if (insUnits is { } u)
        {
            s.Append(CultureInfo.InvariantCulture, $"9\n$INSUNITS\n70\n{u}\n");
        }

        s.Append("0\nENDSEC\n");
        if (blocks.Length > 0)
        {
            s.Append("0\nSECTION\n2\nBLOCKS\n").Append(blocks).Append("0\nENDSEC\n");
        }

        return s.Append("0\nSECTION\n2\nENTITIES\n").Append(entities).Append("0\nENDSEC\n0\nEOF\n").ToString();
    }

    /// <summary>One DXF entity: "0 TYPE" then each group code and value.</summary>
    public static string Entity(string type, params (int Code, object Value)[] groups)
    {
        var s = new StringBuilder($"0\n{type}\n");
        foreach (var (code, value) in groups)
        {
            s.Append(CultureInfo.InvariantCulture, $"{code}\n{Convert.ToString(value, CultureInfo.InvariantCulture)}\n");
        }

        return s.ToString();
    }

    public static string LwPolyline(bool closed, params (double X, double Y, double Bulge)[] vertices)
    {
        var groups = new List<(int, object)> { (5, "2F"), (8, "0"), (90, vertices.Length), (70, closed ? 1 : 0) };
        foreach (var (x, y, b) in vertices)
        {
            groups.Add((10, x));
            groups.Add((20, y));
            if (b != 0)
            {
                groups.Add((42, b));
            }
        }

        return Entity("LWPOLYLINE", [.. groups]);
    }

    /// <summary>An SVG whose user unit is one millimetre (width and height in mm equal to the viewBox).</summary>
    public static string Svg(string body, double size = 100) =>
        string.Create(CultureInfo.InvariantCulture, $"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}mm\" height=\"{size}mm\" viewBox=\"0 0 {size} {size}\">\n{body}\n</svg>");

    public static double Length(IReadOnlyList<DrawingPoint> points)
    {
        var length = 0.0;
        for (var i = 1; i < points.Count; i++)
        {
            length += Math.Sqrt(Math.Pow(points[i].X - points[i - 1].X, 2) + Math.Pow(points[i].Y - points[i - 1].Y, 2));
        }

        return length;
    }

    /// <summary>Length of a drawing's paths flattened far finer than any test tolerance, mm.</summary>
    public static double FineLength(Drawing drawing) => drawing.Paths.Sum(p => Length(p.Flatten(1e-7)));

    /// <summary>Length burned by a plan, mm, summed here from its vertices.</summary>
    public static double BurnLengthMm(VectorPlan plan) =>
        plan.Paths.Sum(p => Enumerable.Range(1, p.Points.Count - 1).Sum(i => Distance(p.Points[i - 1], p.Points[i]))) * MicrostepUm / 1000;

    /// <summary>Laser-off travel of a plan, mm, summed here from its paths' ends.</summary>
    public static double TravelMm(VectorPlan plan)
    {
        var travel = 0.0;
        var at = plan.Start;
        foreach (var p in plan.Paths)
        {
            travel += Distance(at, p.Start);
            at = p.End;
        }

        return travel * MicrostepUm / 1000;
    }

    public static double Distance(StagePoint a, StagePoint b) => Math.Sqrt(Math.Pow(a.X - b.X, 2) + Math.Pow(a.Y - b.Y, 2));

    /// <summary>Microsteps of a millimetre position, rounded once half away from zero: what the stage must be sent.</summary>
    public static long Microsteps(double mm) => (long)Math.Round(mm * 1000 / MicrostepUm, MidpointRounding.AwayFromZero);
}
