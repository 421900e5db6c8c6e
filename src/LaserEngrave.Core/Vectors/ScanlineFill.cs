namespace LaserEngrave.Core.Vectors;

/// <summary>Fills closed contours with horizontal scan lines at a pitch, by the even-odd rule, so holes stay unburned.</summary>
/// <remarks>
/// Scan line k runs at y = top + (k + 1/2) pitch, computed from the unrounded contour and pitch and rounded once, as
/// raster rows are. An edge counts on a scan line when one end lies on or above it and the other below, so a vertex
/// on the line is counted once and a horizontal edge never.
/// </remarks>
public static class ScanlineFill
{
    /// <param name="contours">Closed polylines in unrounded microsteps (last point = first).</param>
    /// <param name="pitchMicrosteps">Distance between scan lines, microsteps (unrounded).</param>
    /// <param name="top">Where scan line 0 is counted from (its y is top + pitch / 2); default the contours' top, so
    /// several areas filled apart can share one set of scan lines.</param>
    public static List<FillRow> Rows(IReadOnlyList<IReadOnlyList<DrawingPoint>> contours, double pitchMicrosteps, double? top = null)
    {
        ArgumentNullException.ThrowIfNull(contours);
        ArgumentOutOfRangeException.ThrowIfLessThanOrEqual(pitchMicrosteps, 0);
        double highest = double.PositiveInfinity, bottom = double.NegativeInfinity;
        foreach (var c in contours)
        {
            foreach (var p in c)
            {
                highest = Math.Min(highest, p.Y);
                bottom = Math.Max(bottom, p.Y);
            }
        }

        if (!(bottom > highest))
        {
            return [];
        }

        var origin = top ?? highest;
        var skipped = Math.Max(0, (int)Math.Floor(((highest - origin) / pitchMicrosteps) - 0.5));
        var count = (int)Math.Min(10_000_000, Math.Ceiling(((bottom - origin) / pitchMicrosteps) - 0.5)) - skipped;
        var crossings = new List<double>[Math.Max(0, count)];
        foreach (var c in contours)
        {
            for (var i = 1; i < c.Count; i++)
            {
                DrawingPoint p = c[i - 1], q = c[i];
                if (p.Y == q.Y)
                {
                    continue;
                }

                // Rows k with y_k in [min y, max y) of the edge.
                double low = Math.Min(p.Y, q.Y), high = Math.Max(p.Y, q.Y);
                var first = Math.Max(0, (int)Math.Ceiling(((low - origin) / pitchMicrosteps) - 0.5) - skipped);
                for (var k = first; k < count; k++)
                {
                    var y = origin + ((k + skipped + 0.5) * pitchMicrosteps);
                    if (y >= high)
                    {
                        break;
                    }

                    if (y < low)
                    {
                        continue;
                    }

                    (crossings[k] ??= []).Add(p.X + ((y - p.Y) * (q.X - p.X) / (q.Y - p.Y)));
                }
            }
        }

        var rows = new List<FillRow>();
        for (var k = 0; k < count; k++)
        {
            if (crossings[k] is not { } xs)
            {
                continue;
            }

            xs.Sort();
            var segments = new List<(long, long)>();
            for (var i = 0; i + 1 < xs.Count; i += 2)
            {
                long x0 = Round(xs[i]), x1 = Round(xs[i + 1]);
                if (x1 > x0)
                {
                    segments.Add((x0, x1));
                }
            }

            if (segments.Count > 0)
            {
                rows.Add(new FillRow(Round(origin + ((k + skipped + 0.5) * pitchMicrosteps)), segments));
            }
        }

        return rows;
    }

    /// <summary>
    /// Splits contours into areas that can be filled one after the other: contours whose boxes overlap, directly or
    /// through others, stay together, so the even-odd rule gives the same rows as over all contours at once.
    /// </summary>
    public static List<List<IReadOnlyList<DrawingPoint>>> Regions(IReadOnlyList<IReadOnlyList<DrawingPoint>> contours)
    {
        ArgumentNullException.ThrowIfNull(contours);
        var boxes = contours.Select(c => (MinX: c.Min(p => p.X), MinY: c.Min(p => p.Y), MaxX: c.Max(p => p.X), MaxY: c.Max(p => p.Y))).ToArray();
        var parent = Enumerable.Range(0, contours.Count).ToArray();
        for (var a = 0; a < contours.Count; a++)
        {
            for (var b = a + 1; b < contours.Count; b++)
            {
                if (boxes[a].MinX <= boxes[b].MaxX && boxes[b].MinX <= boxes[a].MaxX && boxes[a].MinY <= boxes[b].MaxY && boxes[b].MinY <= boxes[a].MaxY)
                {
                    parent[Find(a)] = Find(b);
                }
            }
        }

        return [.. Enumerable.Range(0, contours.Count).GroupBy(Find).Select(g => g.Select(i => contours[i]).ToList())];

        int Find(int i)
        {
            while (parent[i] != i)
            {
                i = parent[i] = parent[parent[i]];
            }

            return i;
        }
    }

    private static long Round(double microsteps) => Geometry.JobGeometry.Round(microsteps);
}
