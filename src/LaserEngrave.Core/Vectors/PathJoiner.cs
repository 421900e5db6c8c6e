namespace LaserEngrave.Core.Vectors;

/// <summary>Joins open paths of one layer that meet end to end at the same microstep into one path, closed when the chain comes back to its start.</summary>
/// <remarks>CAD drawings often draw a hexagon as six LINEs; joined, it is one contour that can be ordered inner-first and burned without stopping.</remarks>
internal static class PathJoiner
{
    public static List<FlatPath> Join(IReadOnlyList<FlatPath> paths)
    {
        var result = new List<FlatPath>();
        var ends = new Dictionary<(string Layer, StagePoint Point), List<int>>();
        for (var i = 0; i < paths.Count; i++)
        {
            if (!paths[i].Closed)
            {
                Index(paths[i].RoundedStart, i);
                Index(paths[i].RoundedEnd, i);
            }
        }

        var used = new bool[paths.Count];
        for (var i = 0; i < paths.Count; i++)
        {
            if (used[i])
            {
                continue;
            }

            used[i] = true;
            var path = paths[i];
            if (path.Closed)
            {
                result.Add(path);
                continue;
            }

            var points = new List<DrawingPoint>(path.Microsteps);
            var joined = 0;
            while (Next(path.Layer, Rounded(points[^1]), out var next, out var reverse))
            {
                var more = reverse ? Enumerable.Reverse(paths[next].Microsteps) : paths[next].Microsteps;
                points.AddRange(more.Skip(1));
                joined++;
            }

            // Then backwards from the start, for chains whose first piece came later in the drawing; the pieces are put
            // in front once at the end (inserting each at the front would copy the chain again for every piece).
            var prefix = new List<List<DrawingPoint>>();
            var head = points[0];
            while (Rounded(head) != Rounded(points[^1]) && Next(path.Layer, Rounded(head), out var previous, out var reverse))
            {
                var before = reverse ? paths[previous].Microsteps : [.. Enumerable.Reverse(paths[previous].Microsteps)];
                prefix.Add([.. before.Take(before.Count - 1)]);
                head = before[0];
                joined++;
            }

            if (prefix.Count > 0)
            {
                var all = new List<DrawingPoint>(points.Count + prefix.Sum(p => p.Count));
                for (var k = prefix.Count - 1; k >= 0; k--)
                {
                    all.AddRange(prefix[k]);
                }

                all.AddRange(points);
                points = all;
            }

            var closed = points.Count > 2 && Rounded(points[0]) == Rounded(points[^1]);
            if (closed)
            {
                points[^1] = points[0];
            }

            result.Add(path with
            {
                Microsteps = points,
                Closed = closed,
                Source = joined == 0 ? path.Source : $"{path.Source} and {joined} joined to it",
            });
        }

        return result;

        void Index(StagePoint point, int i)
        {
            var key = (paths[i].Layer, point);
            if (!ends.TryGetValue(key, out var list))
            {
                ends[key] = list = [];
            }

            list.Add(i);
        }

        // An unused open path with an end at the point; reverse when it is its end (so it must be walked backwards to continue forward).
        bool Next(string layer, StagePoint at, out int index, out bool reverse)
        {
            index = -1;
            reverse = false;
            if (!ends.TryGetValue((layer, at), out var candidates))
            {
                return false;
            }

            foreach (var j in candidates)
            {
                if (!used[j])
                {
                    used[j] = true;
                    index = j;
                    reverse = paths[j].RoundedStart != at;
                    return true;
                }
            }

            return false;
        }
    }

    private static StagePoint Rounded(DrawingPoint p) => new(Geometry.JobGeometry.Round(p.X), Geometry.JobGeometry.Round(p.Y));
}
