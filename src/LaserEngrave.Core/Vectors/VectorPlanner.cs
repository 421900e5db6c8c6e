using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Vectors;

/// <summary>Turns a drawing into a <see cref="VectorPlan"/>: size and place it, flatten curves within the tolerance, round each vertex once, fill, order.</summary>
public static class VectorPlanner
{
    public static VectorPlan Plan(string drawingPath, VectorOptions options, MachineProfile profile) =>
        Plan(DrawingReader.Read(drawingPath), options, profile);

    public static VectorPlan Plan(Drawing drawing, VectorOptions options, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        ArgumentNullException.ThrowIfNull(options);
        ArgumentNullException.ThrowIfNull(profile);
        options.Validate();
        // The profile validator's rule; a profile built in code (never loaded) meets it here.
        if (MachineProfileValidator.EqualMicrosteps(profile) is { } unequal)
        {
            throw new GeometryException($"{profile.Name}: {unequal}");
        }

        var microstepUm = profile.X.MicrostepUm;
        if (drawing.Paths.Count == 0)
        {
            var skipped = drawing.Warnings.Count == 0 ? string.Empty : $" ({string.Join("; ", drawing.Warnings)})";
            throw new DrawingException($"{drawing.Path}: the drawing has nothing to burn{skipped}");
        }

        // Turned and mirrored first: the width asked and the origin are the drawing's as it lies on the stage. A quarter
        // turn or a mirror keeps the axes' directions, so the box's corners give the turned box.
        var orientation = options.Orientation();
        var (min, max) = Oriented(drawing.Bounds(), orientation);
        double width = max.X - min.X, height = max.Y - min.Y;
        double scale = 1;
        if (options.WidthMm is { } wanted)
        {
            scale = width > 0
                ? wanted / width
                : throw new GeometryException($"{drawing.Path}: the drawing has no width to scale to {wanted.ToString(CultureInfo.InvariantCulture)} mm; leave out --width-mm");
        }

        // Drawing millimetres to stage microsteps, unrounded: the bounding box's top-left corner lands on the origin.
        var toStageMm = Affine.Compose(
            Affine.Compose(Affine.Compose(orientation, Affine.Translate(-min.X, -min.Y)), Affine.Scale(scale, scale)),
            Affine.Translate(options.Origin.X, options.Origin.Y));
        var toleranceMm = Units.UmToMm(options.ToleranceUm);
        var selected = drawing.Paths;
        if (options.Layer is { } layer)
        {
            // The layer keeps its place in the whole drawing, so that layers burned one after the other line up.
            selected = [.. drawing.Paths.Where(p => string.Equals(p.Layer, layer, StringComparison.Ordinal))];
            if (selected.Count == 0)
            {
                var layers = drawing.Layers().Select(l => l.Length == 0 ? "(none)" : l);
                throw new DrawingException($"{drawing.Path}: no path on layer \"{layer}\" (its layers: {string.Join(", ", layers)})");
            }
        }

        var flat = new List<FlatPath>(selected.Count);
        long vertices = 0;
        foreach (var path in selected)
        {
            var placed = path.Transform(toStageMm).Flatten(toleranceMm);
            vertices += placed.Count;
            if (vertices > DrawingLimits.MaxVertices)
            {
                throw DrawingLimits.Exceeded(drawing.Path, null, DrawingLimits.MaxVertices, string.Create(CultureInfo.InvariantCulture, $"vertices once its curves are flattened within {options.ToleranceUm:0.###} µm"), "give a larger --tolerance-um or a smaller --width-mm");
            }

            var microsteps = placed.ConvertAll(p => new DrawingPoint(StageUnits.MmToMicrosteps(p.X, microstepUm), StageUnits.MmToMicrosteps(p.Y, microstepUm)));
            if (path.Closed)
            {
                microsteps[^1] = microsteps[0];
            }

            flat.Add(new FlatPath(microsteps, path.Closed, path.Layer, path.Source));
        }

        flat = PathJoiner.Join(flat);
        var paths = new List<StagePath>();
        var rows = new List<FillRow>();
        var start = new StagePoint(
            JobGeometry.Round(StageUnits.MmToMicrosteps(options.Origin.X, microstepUm)),
            JobGeometry.Round(StageUnits.MmToMicrosteps(options.Origin.Y, microstepUm)));
        if (options.Fill is VectorFillMode.Fill or VectorFillMode.Both)
        {
            var contours = flat.Where(f => f.Closed).Select(f => (IReadOnlyList<DrawingPoint>)f.Microsteps).ToList();
            if (contours.Count > 0)
            {
                // Each separate area is filled on its own, serpentine, nearest area next; all on one set of scan lines.
                var top = contours.Min(c => c.Min(p => p.Y));
                var pitch = StageUnits.UmToMicrosteps(options.FillPitchUm, microstepUm);
                var areas = ScanlineFill.Regions(contours).Select(r => ScanlineFill.Rows(r, pitch, top)).Where(r => r.Count > 0).ToList();
                var at = start;
                while (areas.Count > 0)
                {
                    var next = areas.MinBy(a => StagePoint.Distance(at, new StagePoint(a[0].Segments[0].X0, a[0].Y)))!;
                    areas.Remove(next);
                    rows.AddRange(next);
                    paths.AddRange(Serpentine(next));
                    at = paths[^1].End;
                }
            }
        }

        var outlines = options.Fill == VectorFillMode.Fill
            ? flat.Where(f => !f.Closed).Select(f => f.ToStagePath(VectorPathKind.Outline)).ToList()
            : flat.ConvertAll(f => f.ToStagePath(VectorPathKind.Outline));
        var fillEnd = paths.Count > 0 ? paths[^1].End : start;
        var ordered = options.Optimize ? PathOrderer.Order(outlines, fillEnd) : outlines;

        var drawingOrder = paths.Concat(outlines).ToList();
        paths.AddRange(ordered);

        var warnings = new List<string>(drawing.Warnings);
        var fits = Fits(paths, profile);
        if (!fits)
        {
            warnings.Add($"part of the drawing lies outside the stage's travel (0..{profile.X.TravelMm} x 0..{profile.Y.TravelMm} mm)");
        }

        if (paths.Count == 0)
        {
            throw new DrawingException($"{drawing.Path}: the drawing has nothing to burn{(options.Fill == VectorFillMode.Fill ? " with --fill fill (no closed shapes)" : string.Empty)}");
        }

        return new VectorPlan
        {
            DrawingPath = drawing.Path,
            Paths = paths,
            FillRows = rows,
            Start = start,
            MicrostepUm = microstepUm,
            Scale = scale,
            WidthMm = width * scale,
            HeightMm = height * scale,
            ToleranceUm = options.ToleranceUm,
            BurnLengthMm = StageUnits.MicrostepsToMm(paths.Sum(p => p.LengthMicrosteps), microstepUm),
            TravelMm = StageUnits.MicrostepsToMm(PathOrderer.Travel(paths, start), microstepUm),
            TravelDrawingOrderMm = StageUnits.MicrostepsToMm(PathOrderer.Travel(drawingOrder, start), microstepUm),
            FitsTravel = fits,
            Warnings = warnings,
        };
    }

    /// <summary>Fill rows as burn paths: top to bottom, every other row right to left, like the raster planner's serpentine.</summary>
    private static IEnumerable<StagePath> Serpentine(List<FillRow> rows)
    {
        for (var r = 0; r < rows.Count; r++)
        {
            var row = rows[r];
            var segments = r % 2 == 0 ? row.Segments : row.Segments.Reverse();
            foreach (var (x0, x1) in segments)
            {
                StagePoint a = new(x0, row.Y), b = new(x1, row.Y);
                yield return new StagePath(r % 2 == 0 ? [a, b] : [b, a], false, VectorPathKind.Fill, string.Empty, $"fill row {r + 1}");
            }
        }
    }

    private static bool Fits(List<StagePath> paths, MachineProfile profile)
    {
        long maxX = profile.X.TravelMicrosteps, maxY = profile.Y.TravelMicrosteps;
        return paths.All(p => p.Points.All(q => q.X >= 0 && q.Y >= 0 && q.X <= maxX && q.Y <= maxY));
    }

    /// <summary>The box of <paramref name="box"/>'s corners once <paramref name="orientation"/> (a turn, a mirror) has moved them.</summary>
    private static (DrawingPoint Min, DrawingPoint Max) Oriented((DrawingPoint Min, DrawingPoint Max) box, Affine orientation)
    {
        if (orientation.IsIdentity)
        {
            return box;
        }

        var corners = new[] { box.Min, box.Max, new DrawingPoint(box.Min.X, box.Max.Y), new DrawingPoint(box.Max.X, box.Min.Y) }.Select(orientation.Apply).ToList();
        return (new DrawingPoint(corners.Min(c => c.X), corners.Min(c => c.Y)), new DrawingPoint(corners.Max(c => c.X), corners.Max(c => c.Y)));
    }
}
