using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Process;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Simulator.Motion;

namespace LaserEngrave.Simulator.Burn;

/// <summary>
/// Each pulse of a vector job against the paths it should burn: its distance from the nearest path segment, the
/// spacing of consecutive pulses, dwells and pulses off every path.
/// </summary>
/// <remarks>The segments sit in a grid of square cells, so a pulse is compared with the few segments near it only.</remarks>
internal sealed class PathAnalysis
{
    /// <summary>A pulse further than this from every path is off the path (laser on during travel), µm.</summary>
    public const double OffPathUm = 5;

    /// <summary>The spacing is not measured over a laser-on stretch's first and last this many µm.</summary>
    public const double EndsUm = 10;

    private const double CellUm = 100;

    private readonly List<(double Ax, double Ay, double Bx, double By)> _segments = [];
    private readonly Dictionary<(long, long), List<int>> _cells = [];
    private readonly double _xUm;
    private readonly double _yUm;

    public PathAnalysis(IReadOnlyList<StagePath> paths, double xMicrostepUm, double yMicrostepUm)
    {
        _xUm = xMicrostepUm;
        _yUm = yMicrostepUm;
        foreach (var path in paths)
        {
            for (var i = 1; i < path.Points.Count; i++)
            {
                var a = path.Points[i - 1];
                var b = path.Points[i];
                var index = _segments.Count;
                _segments.Add((a.X * _xUm, a.Y * _yUm, b.X * _xUm, b.Y * _yUm));
                var (ax, ay, bx, by) = _segments[^1];
                for (var cx = Cell(Math.Min(ax, bx)); cx <= Cell(Math.Max(ax, bx)); cx++)
                {
                    for (var cy = Cell(Math.Min(ay, by)); cy <= Cell(Math.Max(ay, by)); cy++)
                    {
                        if (!_cells.TryGetValue((cx, cy), out var list))
                        {
                            _cells[(cx, cy)] = list = [];
                        }

                        list.Add(index);
                    }
                }
            }
        }
    }

    public PathReport Analyze(IReadOnlyList<LaserPeriod> periods, AxisTrajectory x, AxisTrajectory y, double burnSpeedMmPerS)
    {
        long pulses = 0, offPath = 0, dwellPulses = 0, spacings = 0;
        int dwells = 0;
        double deviationSum = 0, deviationMax = 0, spacingSum = 0, spacingMin = double.PositiveInfinity, spacingMax = 0, laserOn = 0;
        var slowUmPerS = Units.MmToUm(burnSpeedMmPerS) / 10;
        var stretch = new List<(double X, double Y)>();
        var hz = 0.0;
        foreach (var period in periods)
        {
            laserOn += period.ToSeconds - period.FromSeconds;
            hz = period.FrequencyHz;
            var k = Math.Max(0L, (long)Math.Ceiling(((period.FromSeconds - period.OnSeconds) * hz) - 1e-6));
            stretch.Clear();
            var dwelling = false;
            for (var t = period.OnSeconds + (k / hz); t < period.ToSeconds - 1e-9; t = period.OnSeconds + (++k / hz))
            {
                var px = x.PositionAt(t) * _xUm;
                var py = y.PositionAt(t) * _yUm;
                pulses++;
                stretch.Add((px, py));
                var d = Distance(px, py);
                deviationSum += d;
                deviationMax = Math.Max(deviationMax, d);
                offPath += d > OffPathUm ? 1 : 0;
                var speed = Math.Sqrt(Sq(x.VelocityAt(t) * _xUm) + Sq(y.VelocityAt(t) * _yUm));
                if (speed < slowUmPerS)
                {
                    dwellPulses++;
                    dwells += dwelling ? 0 : 1;
                    dwelling = true;
                }
                else
                {
                    dwelling = false;
                }
            }

            // Spacing along the stretch, leaving out its ends (where the laser's switching, not the motion, decides).
            var along = new double[stretch.Count];
            for (var i = 1; i < stretch.Count; i++)
            {
                along[i] = along[i - 1] + Math.Sqrt(Sq(stretch[i].X - stretch[i - 1].X) + Sq(stretch[i].Y - stretch[i - 1].Y));
            }

            for (var i = 1; i < stretch.Count; i++)
            {
                if (along[i - 1] < EndsUm || along[^1] - along[i] < EndsUm)
                {
                    continue;
                }

                var s = along[i] - along[i - 1];
                spacings++;
                spacingSum += s;
                spacingMin = Math.Min(spacingMin, s);
                spacingMax = Math.Max(spacingMax, s);
            }
        }

        return new PathReport(
            pulses,
            pulses == 0 ? 0 : deviationSum / pulses,
            deviationMax,
            spacings == 0 ? 0 : spacingMin,
            spacings == 0 ? 0 : spacingSum / spacings,
            spacingMax,
            hz > 0 ? PulseArithmetic.SpacingUm(burnSpeedMmPerS, hz) : 0,
            dwells,
            dwellPulses,
            offPath,
            laserOn);
    }

    private static long Cell(double um) => (long)Math.Floor(um / CellUm);

    private static double Sq(double v) => v * v;

    /// <summary>Distance to the nearest segment: those in the pulse's cell and its neighbours, or every one when none is that near.</summary>
    private double Distance(double px, double py)
    {
        var best = double.PositiveInfinity;
        long cx = Cell(px), cy = Cell(py);
        for (var dx = -1; dx <= 1; dx++)
        {
            for (var dy = -1; dy <= 1; dy++)
            {
                if (_cells.TryGetValue((cx + dx, cy + dy), out var list))
                {
                    foreach (var i in list)
                    {
                        best = Math.Min(best, SegmentDistance(px, py, _segments[i]));
                    }
                }
            }
        }

        if (best <= CellUm)
        {
            return best;
        }

        foreach (var segment in _segments)
        {
            best = Math.Min(best, SegmentDistance(px, py, segment));
        }

        return best;
    }

    private static double SegmentDistance(double px, double py, (double Ax, double Ay, double Bx, double By) s)
    {
        double dx = s.Bx - s.Ax, dy = s.By - s.Ay;
        var l2 = (dx * dx) + (dy * dy);
        var t = l2 == 0 ? 0 : Math.Clamp((((px - s.Ax) * dx) + ((py - s.Ay) * dy)) / l2, 0, 1);
        return Math.Sqrt(Sq(px - (s.Ax + (t * dx))) + Sq(py - (s.Ay + (t * dy))));
    }
}
