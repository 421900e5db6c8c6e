using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Preview;

/// <summary>Renders a plan's path: burns in one colour, overscans in another, travels shaded from the start of the job to its end, over a faint outline of the job.</summary>
/// <remarks>
/// The plan is streamed three times (count, laser-off moves, burns) rather than held, so a plan of any size draws in
/// the canvas's memory. Burns are drawn last so travels never hide them. A green dot marks the start, a red ring the end.
/// When image rows are packed closer than two preview pixels, laser-off moves along a row are drawn only on every third
/// preview line, as a hatch, so the white of the image still shows between them.
/// </remarks>
public static class PlanPreview
{
    /// <summary>Largest side accepted, pixels (an RGBA buffer of 64 MB).</summary>
    public const int MaxSidePx = 4096;

    private const int MarginPx = 6;

    private const int HatchSpacingPx = 3;

    public static Rgba Background { get; } = new(255, 255, 255);

    public static Rgba JobFill { get; } = new(243, 243, 243);

    public static Rgba JobOutline { get; } = new(200, 200, 200);

    public static Rgba BurnColour { get; } = new(0, 0, 0);

    public static Rgba OverscanColour { get; } = new(255, 150, 0);

    /// <summary>Colour of the first travel; later travels shade towards <see cref="TravelEndColour"/>.</summary>
    public static Rgba TravelStartColour { get; } = new(0, 170, 255);

    public static Rgba TravelEndColour { get; } = new(190, 0, 190);

    public static Rgba StartMarkerColour { get; } = new(0, 160, 0);

    public static Rgba EndMarkerColour { get; } = new(220, 0, 0);

    /// <summary>Writes a PNG of the plan whose longer side is at most <paramref name="maxSidePx"/>.</summary>
    public static void Render(RasterPlan plan, Stream output, int maxSidePx)
    {
        ArgumentNullException.ThrowIfNull(output);
        Draw(plan, maxSidePx).WritePng(output);
    }

    /// <summary>Writes the preview to the file at <paramref name="path"/>.</summary>
    public static void Render(RasterPlan plan, string path, int maxSidePx)
    {
        using var file = File.Create(path);
        Render(plan, file, maxSidePx);
    }

    /// <summary>Draws the plan on a canvas whose longer side is at most <paramref name="maxSidePx"/>.</summary>
    public static RgbaCanvas Draw(RasterPlan plan, int maxSidePx)
    {
        ArgumentNullException.ThrowIfNull(plan);
        ArgumentOutOfRangeException.ThrowIfLessThan(maxSidePx, (2 * MarginPx) + 1);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(maxSidePx, MaxSidePx);

        var g = plan.Geometry;
        // The bounds hold the whole grid also when a calibration shears it into a parallelogram.
        var (jobLeft, jobTop, jobRight, jobBottom) = g.StageBounds();
        var o = plan.OverscanMicrosteps;
        var left = Math.Min(jobLeft, Math.Max(Math.Min(0, jobLeft), jobLeft - o));
        var right = Math.Max(jobRight, Math.Min(Math.Max(g.TravelXMicrosteps, jobRight), jobRight + o));
        var extent = Math.Max(1, Math.Max(right - left, jobBottom - jobTop));
        var scale = (maxSidePx - (2 * MarginPx) - 1) / (double)extent;
        var map = new Mapping(left, jobTop, scale);
        var canvas = new RgbaCanvas(
            Math.Min(maxSidePx, (int)Math.Ceiling((right - left) * scale) + (2 * MarginPx) + 1),
            Math.Min(maxSidePx, (int)Math.Ceiling((jobBottom - jobTop) * scale) + (2 * MarginPx) + 1),
            Background);

        canvas.FillRect(map.X(jobLeft), map.Y(jobTop), map.X(jobRight), map.Y(jobBottom), JobFill);
        canvas.DrawRect(map.X(jobLeft), map.Y(jobTop), map.X(jobRight), map.Y(jobBottom), JobOutline);

        var counter = new Counter();
        plan.Visit(ref counter);
        if (counter.Moves == 0)
        {
            return canvas;
        }

        // A burn line is about a third of a pixel row thick once a pixel is more than a few preview pixels tall.
        var thickness = Math.Max(1, (int)(g.PitchMicrosteps * scale / 3));
        var hatch = g.PitchMicrosteps * scale < 2 ? HatchSpacingPx : 1;
        var laserOff = new Painter(canvas, map, counter.Moves, burns: false, thickness, hatch);
        plan.Visit(ref laserOff);
        var burns = new Painter(canvas, map, counter.Moves, burns: true, thickness, hatch);
        plan.Visit(ref burns);

        var radius = Math.Max(2, MarginPx - 2);
        canvas.FillCircle(map.X(counter.First.X0), map.Y(counter.First.Y0), radius, StartMarkerColour);
        DrawRing(canvas, map.X(counter.Last.X1), map.Y(counter.Last.Y1), radius, EndMarkerColour);
        return canvas;
    }

    private static void DrawRing(RgbaCanvas canvas, int cx, int cy, int radius, Rgba colour)
    {
        for (var y = -radius; y <= radius; y++)
        {
            for (var x = -radius; x <= radius; x++)
            {
                var d = (x * x) + (y * y);
                if (d <= radius * radius && d > (radius - 2) * (radius - 2))
                {
                    canvas.Set(cx + x, cy + y, colour);
                }
            }
        }
    }

    private readonly record struct Mapping(long Left, long Top, double Scale)
    {
        public int X(long x) => MarginPx + (int)Math.Round((x - Left) * Scale);

        public int Y(long y) => MarginPx + (int)Math.Round((y - Top) * Scale);
    }

    private struct Counter : IMoveVisitor
    {
        public long Moves;
        public Move First;
        public Move Last;

        public void Visit(in Move move)
        {
            if (Moves++ == 0)
            {
                First = move;
            }

            Last = move;
        }
    }

    private struct Painter(RgbaCanvas canvas, Mapping map, long total, bool burns, int thickness, int hatch) : IMoveVisitor
    {
        private long _index;

        public void Visit(in Move move)
        {
            var index = _index++;
            if ((move.Kind == MoveKind.Burn) != burns)
            {
                return;
            }

            int x0 = map.X(move.X0), y0 = map.Y(move.Y0), x1 = map.X(move.X1), y1 = map.Y(move.Y1);
            if (!burns && y0 == y1 && y0 % hatch != 0)
            {
                return;
            }

            switch (move.Kind)
            {
                case MoveKind.Burn:
                    canvas.FillRect(x0, y0 - ((thickness - 1) / 2), x1, y0 + (thickness / 2), BurnColour);
                    break;
                case MoveKind.Overscan:
                    canvas.DrawLine(x0, y0, x1, y1, OverscanColour);
                    break;
                default:
                    canvas.DrawLine(x0, y0, x1, y1, Rgba.Lerp(TravelStartColour, TravelEndColour, total > 1 ? index / (double)(total - 1) : 0));
                    break;
            }
        }
    }
}
