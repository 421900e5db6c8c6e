using System.Diagnostics;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Preview;

/// <summary>
/// The stage's picture of a job, in mm, as the app's stage canvas draws it: every part's moves in burn order (kind and
/// both ends) from the part's program (<see cref="JobPart.Program"/>), what is sent, the boxes of a job's layers or a sweep's cells, the job's rectangle, and which moves a run's progress has
/// burned. The page only draws it.
/// </summary>
/// <remarks>
/// The moves are sent as float32 kind, x0, y0, x1, y1 (mm) per move, at most <see cref="MaxDrawnMoves"/> in all; past the
/// cap the rest is not walked (a large raster has millions of moves) and <see cref="Total"/> says how many there are. The
/// moves are drawn once per job, on first ask; the boxes and the rectangle are made with the picture.
/// </remarks>
public sealed class StagePicture
{
    /// <summary>Moves drawn at most; beyond, the mask picture still shows the whole job.</summary>
    public const int MaxDrawnMoves = 100_000;

    private const int FloatsPerMove = 5;

    private readonly Lazy<DrawnMoves> _moves;

    /// <param name="job">The job to picture; null pictures nothing.</param>
    public StagePicture(EngraveJob? job)
    {
        Job = job;
        Boxes = BoxesOf(job);
        Rect = Boxes.Count > 0 ? Around(Boxes, Units.UmToMm(job!.Spec.Profile.X.MicrostepUm)) : RectOf(job);
        _moves = new Lazy<DrawnMoves>(() => Draw(job));
    }

    /// <summary>The job pictured; null for none.</summary>
    public EngraveJob? Job { get; }

    /// <summary>The boxes named on the stage: each layer of a job of layers (numbered), the labels and every cell of a sweep; none for a single job.</summary>
    public IReadOnlyList<StageBox> Boxes { get; }

    /// <summary>Where the job burns, mm: a single job's own rectangle, or the one around its boxes; null without a job.</summary>
    public StageRect? Rect { get; }

    /// <summary>The moves drawn, float32 kind, x0, y0, x1, y1 (mm) each.</summary>
    public byte[] Moves => _moves.Value.Bytes;

    /// <summary>How many moves are drawn (at most <see cref="MaxDrawnMoves"/>).</summary>
    public int Drawn => _moves.Value.Count;

    /// <summary>How many moves the job has (more than <see cref="Drawn"/> when capped).</summary>
    public long Total => _moves.Value.Total;

    /// <summary>Where each part's moves start among those drawn, in burn order.</summary>
    public IReadOnlyList<StagePart> Parts => _moves.Value.Parts;

    /// <summary>
    /// How many of the drawn moves a run has burned when part <paramref name="part"/> (from 0: the layer or sweep job
    /// under way; 0 for a single job) has done <paramref name="movesDone"/> of its own (plan moves, dots, or a drawing's
    /// strokes); 0 outside the parts.
    /// </summary>
    public long DrawnDone(int part, long movesDone)
    {
        if (part < 0 || part >= Parts.Count)
        {
            return 0;
        }

        var moves = Parts[part];

        // A drawing's run counts strokes and a dot job's dots; the page counts the moves drawn for them (within the part's
        // share of the cap).
        return moves.Start + Math.Min(moves.Count, moves switch
        {
            { StrokeEnds: { Length: > 0 } ends } => movesDone <= 0 ? 0 : ends[(int)Math.Min(movesDone, ends.Length) - 1],
            { DotMarks: { } dots } => dots.After(movesDone),
            _ => Math.Max(0, movesDone),
        });
    }

    /// <summary>Where the machine's position is on the stage, mm; null while either axis is unknown.</summary>
    public static (double X, double Y)? LaserMm(long? xMicrosteps, long? yMicrosteps, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        return xMicrosteps is { } x && yMicrosteps is { } y
            ? (StageUnits.MicrostepsToMm(x, profile.X.MicrostepUm), StageUnits.MicrostepsToMm(y, profile.Y.MicrostepUm))
            : null;
    }

    /// <summary>An image's plan as moves, at most <see cref="MaxDrawnMoves"/>: what was drawn, and how many moves the plan has.</summary>
    /// <remarks>Drawn from its raster program (a dot job's too: its raster plan, kept for the preview, shows the runs its dots burn).</remarks>
    public static (byte[] Bytes, int Drawn, long Total) PlanMoves(PreparedJob? job) =>
        job is null ? ([], 0, 0) : RasterMoves(job.Program(), job.Spec.Profile, job.Statistics.Moves);

    /// <summary>A drawing's strokes as moves (travel, run-up, the path's segments, run-out), and where each stroke's moves end.</summary>
    public static (byte[] Bytes, int Drawn, long Total) DrawingMoves(PreparedDrawing drawing, out int[] strokeMoveEnds)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        return DrawingMoves(drawing.Schedule.Program(), drawing.Plan.Start, drawing.Spec.Profile, out strokeMoveEnds);
    }

    // A raster program's moves: its steps (travels, strokes, plain moves) run the plan's moves in the plan's order, so they
    // are read from the plan, without timing every stroke only to draw it. Past the cap the rest is not walked: the plan's
    // figures say how many moves there are.
    // Each burn move drawn goes to burns, when given: its row, its index among those drawn and its direction.
    private static (byte[] Bytes, int Drawn, long Total) RasterMoves(RasterProgram program, MachineProfile profile, long planned, List<(int Row, int At, bool LeftToRight)>? burns = null)
    {
        var um = Units.UmToMm(profile.X.MicrostepUm);
        var vm = Units.UmToMm(profile.Y.MicrostepUm);

        // Sized by the figures, but filled from the program itself: a dot job's figures count its dots, not its moves.
        var values = new List<float>((int)Math.Min(planned, MaxDrawnMoves) * FloatsPerMove);
        var capped = false;
        bool Add(in Move move)
        {
            if (values.Count >= MaxDrawnMoves * FloatsPerMove)
            {
                capped = true;
                return false;
            }

            if (move.Kind == MoveKind.Burn)
            {
                burns?.Add((move.Row, values.Count / FloatsPerMove, move.X1 > move.X0));
            }

            values.Add((float)move.Kind);
            values.Add((float)(move.X0 * um));
            values.Add((float)(move.Y0 * vm));
            values.Add((float)(move.X1 * um));
            values.Add((float)(move.Y1 * vm));
            return true;
        }

        foreach (var move in program.Plan.Moves())
        {
            if (!Add(move))
            {
                break;
            }
        }

        var drawn = values.Count / FloatsPerMove;
        return (Bytes(values), drawn, capped ? Math.Max(planned, drawn + 1L) : drawn);
    }

    // A dot job is pictured by its raster plan (kept for the preview): the runs its dots burn, not the dots alone; its run
    // counts dots, so the picture keeps which of its moves each dot marks burned.
    private static (byte[] Bytes, int Drawn, long Total) DotMoves(PreparedJob job, out DotMarks dots)
    {
        var burns = new List<(int Row, int At, bool LeftToRight)>();
        var picture = RasterMoves(job.Program(), job.Spec.Profile, job.Statistics.Moves, burns);
        dots = DotMarks.Of(job.Dots!, burns, picture.Drawn);
        return picture;
    }

    // A drawing program's steps as moves: each stroke's travel (the run's first from the plan's start: the positioning goes
    // from wherever the stage stands), its run-up, its path's segments and its run-out; where each stroke's moves end.
    private static (byte[] Bytes, int Drawn, long Total) DrawingMoves(DrawingProgram program, StagePoint start, MachineProfile profile, out int[] strokeMoveEnds)
    {
        var um = Units.UmToMm(profile.X.MicrostepUm);
        var vm = Units.UmToMm(profile.Y.MicrostepUm);
        var values = new List<float>();
        var ends = new int[program.StrokeCount];
        var moves = 0;
        long total = 0;
        void Add(MoveKind kind, StagePoint a, StagePoint b)
        {
            if (a == b)
            {
                return;
            }

            total++;
            if (moves < MaxDrawnMoves)
            {
                values.AddRange([(float)kind, (float)(a.X * um), (float)(a.Y * vm), (float)(b.X * um), (float)(b.Y * vm)]);
                moves++;
            }
        }

        foreach (var step in program.Steps())
        {
            var stroke = step.Stroke;
            var points = stroke.Path.Points;
            Add(MoveKind.Travel, step.Travel.From ?? start, step.Travel.To);
            Add(MoveKind.Overscan, step.Travel.To, points[0]);
            for (var k = 1; k < points.Count; k++)
            {
                Add(MoveKind.Burn, points[k - 1], points[k]);
            }

            Add(MoveKind.Overscan, points[^1], stroke.RestEnd);
            ends[step.Index] = moves;
        }

        strokeMoveEnds = ends;
        return (Bytes(values), moves, total);
    }

    /// <summary>Where a planned image burns, mm: its pixel grid's outer edges, as the planner places them.</summary>
    public static (double X, double Y, double W, double H) Edges(PreparedJob job)
    {
        ArgumentNullException.ThrowIfNull(job);
        var g = job.Geometry.Geometry;
        var um = Units.UmToMm(job.Spec.Profile.X.MicrostepUm);
        var vm = Units.UmToMm(job.Spec.Profile.Y.MicrostepUm);
        var left = g.EdgeX(0) * um;
        var top = g.EdgeY(0) * vm;
        return (left, top, (g.EdgeX(g.WidthPx) * um) - left, (g.EdgeY(g.HeightPx) * vm) - top);
    }

    // Every part's moves from its program, one part after the other, each kept within what is left of the cap.
    private static DrawnMoves Draw(EngraveJob? job)
    {
        if (job is null)
        {
            return new DrawnMoves([], 0, 0, []);
        }

        using var all = new MemoryStream();
        var parts = new List<StagePart>(job.Parts.Count);
        var drawn = 0;
        long total = 0;
        foreach (var part in job.Parts)
        {
            int[]? ends = null;
            DotMarks? dots = null;
            var (bytes, count, moves) = part switch
            {
                RasterPart raster => RasterMoves(raster.Program(), part.Spec.Profile, part.Moves),
                DotPart dot => DotMoves(dot.Image, out dots),
                DrawingPart drawing => DrawingMoves(drawing.Program(), drawing.Drawing.Plan.Start, part.Spec.Profile, out ends),
                var other => throw new UnreachableException($"no picture of a {other.GetType().Name}"),
            };
            var kept = Math.Max(0, Math.Min(count, MaxDrawnMoves - drawn));
            all.Write(bytes, 0, kept * FloatsPerMove * sizeof(float));
            parts.Add(new StagePart(drawn, kept, ends, dots));
            drawn += kept;
            total += moves;
        }

        return new DrawnMoves(all.ToArray(), drawn, total, [.. parts]);
    }

    // The kinds are named here because they are drawn differently: a job of layers numbers its layers, a sweep names
    // each cell by its values, a single job has no box of its own.
    private static IReadOnlyList<StageBox> BoxesOf(EngraveJob? job) => job switch
    {
        LayersJob layers => [.. layers.Parts.Select((l, i) => new StageBox(l.Spec.Origin.X, l.Spec.Origin.Y, l.SizeMm.WidthMm, l.SizeMm.HeightMm, $"{i + 1} {l.Layer.Name}", l.FitsTravel))],
        SweepJob sweep => SweepBoxes(sweep.Plan),
        _ => [],
    };

    private static StageBox[] SweepBoxes(SweepPlan plan)
    {
        var boxes = new List<StageBox>(plan.Cells.Count + 1);
        if (plan.Labels is { } labels)
        {
            boxes.Add(Box(labels, "labels"));
        }

        foreach (var cell in plan.Cells)
        {
            boxes.Add(Box(cell.Job, Sweeps.SweepParameters.Label(cell.Parameters)));
        }

        return [.. boxes];

        static StageBox Box(PreparedJob job, string name)
        {
            var (x, y, w, h) = Edges(job);
            return new StageBox(x, y, w, h, name, job.Geometry.FitsTravel);
        }
    }

    // A single job's rectangle: a drawing's origin and planned size, an image's pixel grid; the pitch the page snaps a drag to.
    private static StageRect? RectOf(EngraveJob? job)
    {
        if (job is null)
        {
            return null;
        }

        var part = job.Parts[0];
        if (part is DrawingPart { Drawing: var drawing })
        {
            var plan = drawing.Plan;
            return new StageRect(drawing.Spec.Origin.X, drawing.Spec.Origin.Y, plan.WidthMm, plan.HeightMm, drawing.FitsTravel, Units.UmToMm(plan.MicrostepUm));
        }

        var image = ((ImagePart)part).Image;
        var (x, y, w, h) = Edges(image);
        return new StageRect(x, y, w, h, image.Geometry.FitsTravel, Units.UmToMm(image.Geometry.PitchUm));
    }

    // The box around every layer or cell (not dragged: each has its own origin).
    private static StageRect Around(IReadOnlyList<StageBox> boxes, double pitchMm) => new(
        boxes.Min(b => b.X),
        boxes.Min(b => b.Y),
        boxes.Max(b => b.X + b.W) - boxes.Min(b => b.X),
        boxes.Max(b => b.Y + b.H) - boxes.Min(b => b.Y),
        boxes.All(b => b.Fits),
        pitchMm);

    private static byte[] Bytes(List<float> values)
    {
        var bytes = new byte[values.Count * sizeof(float)];
        Buffer.BlockCopy(values.ToArray(), 0, bytes, 0, bytes.Length);
        return bytes;
    }

    private sealed record DrawnMoves(byte[] Bytes, int Count, long Total, StagePart[] Parts);
}

/// <summary>One named box on the stage, mm (a layer, the sweep's labels or a cell), as the page draws it.</summary>
public sealed record StageBox(double X, double Y, double W, double H, string Name, bool Fits);

/// <summary>The job's rectangle on the stage, mm, whether it fits the travel, and the pitch (mm) a drag snaps to.</summary>
public sealed record StageRect(double X, double Y, double W, double H, bool Fits, double Pitch);

/// <summary>
/// Where a part's moves start among those drawn, how many are drawn, for a drawing where each stroke's moves end (within
/// the part), and for a dot job how many of its moves its dots mark burned.
/// </summary>
public sealed record StagePart(int Start, int Count, int[]? StrokeEnds, DotMarks? DotMarks = null);
