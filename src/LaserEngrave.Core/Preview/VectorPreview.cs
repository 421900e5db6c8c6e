using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Preview;

/// <summary>Renders a vector plan: burned paths in one colour, laser-off travel between them shaded from the start of the job to its end.</summary>
/// <remarks>The same colours and markers as <see cref="PlanPreview"/>: a green dot at the start, a red ring where the last path ends.</remarks>
public static class VectorPreview
{
    private const int MarginPx = 6;

    public static void Render(VectorPlan plan, string path, int maxSidePx)
    {
        using var file = File.Create(path);
        Draw(plan, maxSidePx).WritePng(file);
    }

    public static RgbaCanvas Draw(VectorPlan plan, int maxSidePx)
    {
        ArgumentNullException.ThrowIfNull(plan);
        ArgumentOutOfRangeException.ThrowIfLessThan(maxSidePx, (2 * MarginPx) + 1);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(maxSidePx, PlanPreview.MaxSidePx);

        long left = plan.Start.X, right = plan.Start.X, top = plan.Start.Y, bottom = plan.Start.Y;
        foreach (var p in plan.Paths.SelectMany(p => p.Points))
        {
            left = Math.Min(left, p.X);
            right = Math.Max(right, p.X);
            top = Math.Min(top, p.Y);
            bottom = Math.Max(bottom, p.Y);
        }

        var extent = Math.Max(1, Math.Max(right - left, bottom - top));
        var scale = (maxSidePx - (2 * MarginPx) - 1) / (double)extent;
        var canvas = new RgbaCanvas(
            Math.Min(maxSidePx, (int)Math.Ceiling((right - left) * scale) + (2 * MarginPx) + 1),
            Math.Min(maxSidePx, (int)Math.Ceiling((bottom - top) * scale) + (2 * MarginPx) + 1),
            PlanPreview.Background);
        int X(long x) => MarginPx + (int)Math.Round((x - left) * scale);
        int Y(long y) => MarginPx + (int)Math.Round((y - top) * scale);

        var at = plan.Start;
        for (var i = 0; i < plan.Paths.Count; i++)
        {
            var colour = Rgba.Lerp(PlanPreview.TravelStartColour, PlanPreview.TravelEndColour, plan.Paths.Count > 1 ? i / (double)(plan.Paths.Count - 1) : 0);
            var start = plan.Paths[i].Start;
            if (start != at)
            {
                canvas.DrawLine(X(at.X), Y(at.Y), X(start.X), Y(start.Y), colour);
            }

            at = plan.Paths[i].End;
        }

        // Burns last, so travel never hides them.
        foreach (var path in plan.Paths)
        {
            for (var i = 1; i < path.Points.Count; i++)
            {
                canvas.DrawLine(X(path.Points[i - 1].X), Y(path.Points[i - 1].Y), X(path.Points[i].X), Y(path.Points[i].Y), PlanPreview.BurnColour);
            }
        }

        var radius = Math.Max(2, MarginPx - 2);
        canvas.FillCircle(X(plan.Start.X), Y(plan.Start.Y), radius, PlanPreview.StartMarkerColour);
        for (var y = -radius; y <= radius; y++)
        {
            for (var x = -radius; x <= radius; x++)
            {
                var d = (x * x) + (y * y);
                if (d <= radius * radius && d > (radius - 2) * (radius - 2))
                {
                    canvas.Set(X(at.X) + x, Y(at.Y) + y, PlanPreview.EndMarkerColour);
                }
            }
        }

        return canvas;
    }
}
