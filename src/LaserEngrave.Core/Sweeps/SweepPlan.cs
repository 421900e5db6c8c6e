using System.Globalization;
using System.Security.Cryptography;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Sweeps;

/// <summary>A sweep laid out on the stage: every cell's job, and the labels' job, in the order they are burned.</summary>
/// <remarks>
/// <para>
/// The grid's top-left corner is <see cref="SweepSpec.Origin"/>. With labels, a strip on the left holds each row's value
/// and a strip on top each column's (digits of <see cref="TinyFont"/>, one job in raster mode at the base process), and
/// the cells begin right and below them. Cell (r, c) has its top-left corner at grid + (c (cell + spacing), r (cell + spacing)).
/// A cell of side s at pitch p has n = max(1, round(s / p)) pixels a side: all black (square), every other row (lines),
/// or every other pixel of every other row (dots). Cells are burned row by row, left to right, after the labels.
/// </para>
/// <para>docs/process.md ("Parameter sweeps") has a worked example.</para>
/// </remarks>
public sealed class SweepPlan
{
    /// <summary>The most cells a sweep may have.</summary>
    public const int MaxCells = 400;

    /// <summary>Label glyph height as a share of the cell side.</summary>
    private const double LabelHeightShare = 0.4;

    private SweepPlan(SweepSpec spec, IReadOnlyList<SweepCell> cells, PreparedJob? labels, double gridXMm, double gridYMm)
    {
        Spec = spec;
        Cells = cells;
        Labels = labels;
        GridXMm = gridXMm;
        GridYMm = gridYMm;
    }

    public SweepSpec Spec { get; }

    /// <summary>The cells in the order they are burned: row by row, left to right.</summary>
    public IReadOnlyList<SweepCell> Cells { get; }

    /// <summary>The labels' job (null without labels).</summary>
    public PreparedJob? Labels { get; }

    /// <summary>Stage position of the first cell's top-left corner, mm.</summary>
    public double GridXMm { get; }

    public double GridYMm { get; }

    public int RowCount => Spec.Rows.Values.Count;

    public int ColumnCount => Spec.Columns?.Values.Count ?? 1;

    /// <summary>The estimated engraving time of every cell (all its passes) and of the labels, s.</summary>
    public double EngravingSeconds => Jobs().Sum(j => j.Statistics.EngravingSeconds * j.Spec.Passes);

    /// <summary>
    /// The estimate of the whole sweep, s: the first job's preparation (preflight, homing from the far end, the travel to
    /// it), every later job's preflight without homing and travel from where the one before ended, every job's passes, and
    /// the focus moves of a focal series (<see cref="FocusMovesSeconds"/>).
    /// </summary>
    public double EstimatedSeconds
    {
        get
        {
            var total = 0.0;
            (long X, long Y)? end = null;
            foreach (var job in Jobs())
            {
                var (start, stop) = Ends(job);
                var statistics = job.Statistics;
                total += end is { } from
                    ? (job.Plan.Timing ?? TimedSwitching.For(job.Spec.Process, job.Spec.Profile, job.Plan.Geometry.MicrostepUm)).PreparationSeconds(start.X, start.Y, home: false, from: from)
                    : statistics.PreparationSeconds;
                total += (job.Spec.Passes * statistics.EngravingSeconds) + ((job.Spec.Passes - 1) * statistics.PassSetupSeconds);
                end = stop;
            }

            return total + FocusMovesSeconds();
        }
    }

    /// <summary>
    /// The focus moves of a focal series, s: from the visible focus to the labels' (the visible focus) and each cell's Z, and
    /// back, each the laser's switch-off acknowledged, the move command, the motion (a trapezoid at z.speedMmPerS) and its
    /// reply; and Z's identification and settings before the first. Homing Z, which the first move does when Z is not homed, is left out: where Z stands before is not known.
    /// </summary>
    public double FocusMovesSeconds()
    {
        if (Spec.Profile.Z is not { } z || Cells.All(c => c.FocusZMicrosteps is null))
        {
            return 0;
        }

        var timing = TimedSwitching.For(Spec.Process, Spec.Profile, z.MicrostepUm);
        var speed = StageUnits.SpeedMicrostepsPerS(z.SpeedData);
        var acceleration = StageUnits.AccelerationMicrostepsPerS2(z.AccelerationData(Spec.Profile.AccelerationMmPerS2));
        var focus = z.MicrostepsAt(0);
        var total = 0.0;
        var at = focus;
        foreach (var target in Cells.Select(c => c.FocusZMicrosteps ?? at).Append(focus))
        {
            var motion = target == at ? 0 : new Motion.TrapezoidProfile(Math.Abs(target - at), speed, acceleration).Duration;
            total += timing.OffRoundTripSeconds + timing.StageCommandSeconds + motion + timing.StageReplySeconds;
            at = target;
        }

        // Before the first move Z is identified (device ID, firmware, Device Mode, its settings and position: 8 round trips,
        // as every axis in a preflight) and given its acceleration and speed (2).
        var preparation = 10 * (timing.StageCommandSeconds + timing.StageReplySeconds);
        return preparation + total + (Labels is null ? 0 : timing.OffRoundTripSeconds + timing.StageCommandSeconds + timing.StageReplySeconds);
    }

    /// <summary>The jobs in the order they are burned: the labels, then the cells.</summary>
    public IEnumerable<PreparedJob> Jobs() => Labels is null ? Cells.Select(c => c.Job) : Cells.Select(c => c.Job).Prepend(Labels);

    /// <summary>The SHA-256 of a generated mask's bits (it has no file), lower-case hex: the run log's image hash for a cell.</summary>
    public static string MaskSha256(BitMask mask)
    {
        ArgumentNullException.ThrowIfNull(mask);
        using var hash = IncrementalHash.CreateHash(HashAlgorithmName.SHA256);
        Span<byte> size = stackalloc byte[8];
        BitConverter.TryWriteBytes(size[..4], mask.Width);
        BitConverter.TryWriteBytes(size[4..], mask.Height);
        hash.AppendData(size);
        var bytes = new byte[mask.WordsPerRow * sizeof(ulong)];
        for (var y = 0; y < mask.Height; y++)
        {
            System.Runtime.InteropServices.MemoryMarshal.AsBytes(mask.ReadRow(y)).CopyTo(bytes);
            hash.AppendData(bytes);
        }

        return Convert.ToHexStringLower(hash.GetHashAndReset());
    }

    /// <summary>Lays the sweep out and plans every cell; throws <see cref="SweepException"/> with one line naming the value (or the cell) and the problem.</summary>
    public static SweepPlan Build(SweepSpec spec)
    {
        ArgumentNullException.ThrowIfNull(spec);
        var profile = spec.Profile;
        var limits = MachineLimits.Of(profile);
        var microstepUm = Math.Max(profile.X.MicrostepUm, profile.Y.MicrostepUm);
        Validate(spec, limits, microstepUm);

        var cellUm = Units.MmToUm(spec.CellMm);
        var columns = spec.Columns;
        var rowTexts = spec.Rows.Values.Select(Label).ToList();
        var columnTexts = columns?.Values.Select(Label).ToList() ?? [];

        // Labels: glyphs 0.4 of a cell tall, narrower when a column's label would not fit over its cell and the spacing.
        var labelPitchUm = 0.0;
        double stripXMm = 0, stripYMm = 0;
        if (spec.Labels)
        {
            labelPitchUm = cellUm * LabelHeightShare / TinyFont.GlyphHeight;
            foreach (var text in columnTexts)
            {
                labelPitchUm = Math.Min(labelPitchUm, Units.MmToUm(spec.CellMm + spec.SpacingMm) / (TinyFont.Width(text) + 1));
            }

            if (labelPitchUm < microstepUm)
            {
                throw new SweepException($"--labels: cells of {N(spec.CellMm)} mm leave labels pixels of {N(labelPitchUm)} µm, below one microstep; make the cells larger or leave the labels out");
            }

            var gap = Math.Max(spec.SpacingMm, Units.UmToMm(2 * labelPitchUm));
            stripXMm = Units.StepsToMm(rowTexts.Max(TinyFont.Width), labelPitchUm) + gap;
            stripYMm = columns is null ? 0 : Units.StepsToMm(TinyFont.GlyphHeight, labelPitchUm) + gap;
        }

        var gridX = spec.Origin.X + stripXMm;
        var gridY = spec.Origin.Y + stripYMm;
        var stepMm = spec.CellMm + spec.SpacingMm;
        var cells = new List<SweepCell>();
        for (var r = 0; r < spec.Rows.Values.Count; r++)
        {
            for (var c = 0; c < (columns?.Values.Count ?? 1); c++)
            {
                var parameters = new Dictionary<string, double> { [spec.Rows.Parameter.LogKey()] = spec.Rows.Values[r] };
                if (columns is not null)
                {
                    parameters[columns.Parameter.LogKey()] = columns.Values[c];
                }

                var origin = new OriginMm(gridX + (c * stepMm), gridY + (r * stepMm));
                cells.Add(PlanCell(spec, r, c, parameters, origin));
            }
        }

        PreparedJob? labels = null;
        if (spec.Labels)
        {
            // Each label centred on its row or column, in label pixels from the grid's corner; the mask holds them all.
            int Px(double mm) => (int)Math.Round(Units.MmToSteps(mm, labelPitchUm));
            var placed = new List<(string Text, int X, int Y)>();
            for (var r = 0; r < rowTexts.Count; r++)
            {
                placed.Add((rowTexts[r], 0, Px(gridY - spec.Origin.Y + (r * stepMm) + (spec.CellMm / 2)) - (TinyFont.GlyphHeight / 2)));
            }

            for (var c = 0; c < columnTexts.Count; c++)
            {
                placed.Add((columnTexts[c], Px(gridX - spec.Origin.X + (c * stepMm) + (spec.CellMm / 2)) - (TinyFont.Width(columnTexts[c]) / 2), 0));
            }

            var mask = new BitMask(
                Math.Max(1, placed.Max(p => p.X + TinyFont.Width(p.Text))),
                Math.Max(1, placed.Max(p => p.Y + TinyFont.GlyphHeight)));
            foreach (var (text, x, y) in placed)
            {
                TinyFont.Draw(mask, text, x, y);
            }

            var process = spec.Process with { Mode = PlanMode.Raster, PulsesPerDot = 1, DotPitchMicrosteps = 0, DotSettleMs = 0 };
            labels = Prepare(spec, "sweep labels", mask, SizeSpec.Pitch(labelPitchUm), spec.Origin, process, 1, "the labels");
        }

        return new SweepPlan(spec, cells, labels, gridX, gridY);
    }

    // Where a job's plan starts and ends on the stage, microsteps (its first and last dot in dot mode).
    private static ((long X, long Y) Start, (long X, long Y) End) Ends(PreparedJob job)
    {
        // The plan's statistics hold its ends already; the app reads the estimate on every render, so no walk of the plan.
        if (job.Statistics.Ends is { } ends)
        {
            return ends;
        }

        if (job.Dots is { } dots)
        {
            var first = dots.Dots().First();
            var last = dots.Dots().Last();
            return ((first.X, first.Y), (last.X, last.Y));
        }

        var moves = job.Plan.Moves();
        var a = moves.First();
        var z = moves.Last();
        return ((a.X0, a.Y0), (z.X1, z.Y1));
    }

    /// <summary>The cell's mask: a square of n x n pixels, filled, lines or dots.</summary>
    public static BitMask CellMask(SweepPattern pattern, int n)
    {
        var mask = new BitMask(n, n);
        for (var y = 0; y < n; y++)
        {
            for (var x = 0; x < n; x++)
            {
                mask[x, y] = pattern switch
                {
                    SweepPattern.Lines => y % 2 == 0,
                    SweepPattern.Dots => y % 2 == 0 && x % 2 == 0,
                    _ => true,
                };
            }
        }

        return mask;
    }

    private static SweepCell PlanCell(SweepSpec spec, int row, int column, Dictionary<string, double> parameters, OriginMm origin)
    {
        var process = spec.Process;
        var passes = spec.Passes;
        var pitch = spec.PitchUm;
        double? focusUm = null;
        foreach (var (key, value) in parameters)
        {
            switch (key)
            {
                case "speedMmPerS": process = process with { BurnSpeedMmPerS = value }; break;
                case "frequencyHz": process = process with { LaserFrequencyHz = value }; break;
                case "passes": passes = (int)value; break;
                case "pulsesPerDot": process = process with { PulsesPerDot = (int)value }; break;
                case "pitchUm": pitch = value; break;
                case "focusUm": focusUm = value; break;
                default: throw new InvalidOperationException($"unknown sweep parameter {key}");
            }
        }

        BitMask mask;
        if (spec.CellImage is { } image && spec.Pattern == SweepPattern.Image)
        {
            mask = image;
            pitch = ImagePitchUm(spec, image);
        }
        else
        {
            mask = CellMask(spec.Pattern, Math.Max(1, (int)Math.Round(Units.MmToSteps(spec.CellMm, pitch))));
        }

        var job = Prepare(spec, $"sweep cell r{row + 1} c{column + 1}", mask, SizeSpec.Pitch(pitch), origin, process, passes, SweepCell.Describe(row, column, parameters));
        return new SweepCell(row, column, parameters, job)
        {
            FocusZMicrosteps = focusUm is { } offset ? spec.Profile.Z!.MicrostepsAt(offset) : null,
        };
    }

    private static PreparedJob Prepare(SweepSpec spec, string name, BitMask mask, SizeSpec size, OriginMm origin, ProcessSettings process, int passes, string what)
    {
        var info = new ImageInfo(name, ImageFormat.Pbm, 1, 2, mask.Width, mask.Height, 0, null, null, RowOrder.TopDown, "none", false);
        var jobSpec = new JobSpec
        {
            ImagePath = name,
            Size = size,
            Origin = origin,
            Plan = spec.Plan,
            Process = process,
            Profile = spec.Profile,
            Passes = passes,
        };
        PreparedJob job;
        try
        {
            job = PreparedJob.Prepare(jobSpec, info, mask);
        }
        catch (Exception ex) when (ex is PlanException or GeometryException)
        {
            throw new SweepException($"{what}: {ex.Message}", ex);
        }

        if (!job.Geometry.FitsTravel)
        {
            throw new SweepException($"{what} reaches past the stage travel ({N(job.Spec.Profile.X.TravelMm)} x {N(job.Spec.Profile.Y.TravelMm)} mm): move the sweep (--origin-mm) or make it smaller");
        }

        if (job.EngraveProblem is { } problem)
        {
            throw new SweepException($"{what}: {problem}");
        }

        return job;
    }

    private static void Validate(SweepSpec spec, MachineLimits limits, double microstepUm)
    {
        var travel = Math.Min(limits.TravelXMm, limits.TravelYMm);
        if (!(spec.CellMm > 0 && spec.CellMm <= travel))
        {
            throw new SweepException($"--cell-mm {N(spec.CellMm)}: must be above 0 and at most {N(travel)} mm (the travel)");
        }

        if (!(spec.SpacingMm >= 0 && spec.SpacingMm <= travel))
        {
            throw new SweepException($"--spacing-mm {N(spec.SpacingMm)}: must be 0..{N(travel)} mm");
        }

        if (spec.Pattern == SweepPattern.Image)
        {
            if (spec.CellImage is not { } image)
            {
                throw new SweepException("--pattern image needs the cell's image: --cell-image FILE");
            }

            if (spec.Rows.Parameter == SweepParameter.Pitch || spec.Columns?.Parameter == SweepParameter.Pitch)
            {
                throw new SweepException("--pattern image sizes the image to the cell (its larger side), so its pitch cannot be swept; sweep the cell size by runs of their own");
            }

            CheckPitch(ImagePitchUm(spec, image), $"--cell-image {spec.CellImageName} ({image.Width} x {image.Height} px over {N(spec.CellMm)} mm): a pixel of");
        }
        else
        {
            CheckPitch(spec.PitchUm, "--pitch-um");
        }

        if (JobRules.Passes(spec.Passes) is { } passes)
        {
            throw new SweepException($"--passes {spec.Passes}: {passes}");
        }

        // The base of every cell meets the job rules (the command line and the app check it so before; a spec built otherwise is checked here).
        var basis = JobSettings.From(spec.Process, spec.Plan) with
        {
            OriginXMm = spec.Origin.X,
            OriginYMm = spec.Origin.Y,
            Passes = spec.Passes,
            SizeMode = SizeMode.Pitch,
            PitchUm = spec.Pattern == SweepPattern.Image ? microstepUm : spec.PitchUm,
        };
        if (JobRules.Check(basis, limits) is [var wrong, ..])
        {
            throw new SweepException(wrong.Message);
        }

        if (spec.Columns is { } columns && columns.Parameter == spec.Rows.Parameter)
        {
            throw new SweepException($"--rows and --columns both vary {columns.Parameter.CliName()}: vary two different parameters, or one");
        }

        var cells = spec.Rows.Values.Count * (spec.Columns?.Values.Count ?? 1);
        if (spec.Rows.Values.Count == 0 || spec.Columns is { Values.Count: 0 })
        {
            throw new SweepException("a sweep needs at least one value along its rows and its columns");
        }

        if (cells > MaxCells)
        {
            throw new SweepException($"{cells} cells: a sweep has at most {MaxCells}");
        }

        foreach (var (axis, option) in new[] { (spec.Rows, spec.RowsOption), (spec.Columns, "--columns") })
        {
            if (axis is null)
            {
                continue;
            }

            foreach (var value in axis.Values)
            {
                var cell = axis.Parameter switch
                {
                    SweepParameter.Speed => basis with { BurnSpeedMmPerS = value },
                    SweepParameter.Frequency => basis with { LaserFrequencyHz = value },
                    SweepParameter.Passes => basis with { Passes = (int)Math.Clamp(value, int.MinValue, int.MaxValue) },
                    SweepParameter.PulsesPerDot => basis with { PulsesPerDot = (int)Math.Clamp(value, int.MinValue, int.MaxValue), Mode = PlanMode.Dots },
                    SweepParameter.Pitch => basis with { PitchUm = value },
                    _ => basis,
                };
                var problem = JobRules.Check(cell, limits).FirstOrDefault()?.Rule ?? axis.Parameter switch
                {
                    SweepParameter.PulsesPerDot when spec.Process.Mode != PlanMode.Dots => "pulses per dot are swept in dot mode only: add --mode dots",
                    SweepParameter.Pitch when !(value <= Units.MmToUm(spec.CellMm)) => $"must be {N(microstepUm)} µm (a microstep) .. {N(Units.MmToUm(spec.CellMm))} µm (the cell)",
                    SweepParameter.Focus when spec.Profile.Z is null => "the machine has no Z axis: add a \"z\" section to the machine profile (docs/machine-profile.md) to sweep the focus",
                    SweepParameter.Focus when spec.Profile.Z.OffsetProblem(value) is { } outside => outside,
                    _ => null,
                };
                if (problem is not null)
                {
                    var given = option == "--focus-um" ? string.Join(',', axis.Values.Select(N)) : axis.ToString();
                    throw new SweepException($"{option} {given}: {axis.Parameter.CliName()} {N(value)} {axis.Parameter.Unit()}".TrimEnd() + $": {problem}");
                }
            }
        }

        void CheckPitch(double pitch, string option)
        {
            if (!(pitch >= microstepUm && pitch <= Units.MmToUm(spec.CellMm)))
            {
                throw new SweepException($"{option} {N(pitch)}: must be {N(microstepUm)} µm (a microstep) .. {N(Units.MmToUm(spec.CellMm))} µm (the cell)");
            }
        }
    }

    // The image's larger side spans the cell.
    private static double ImagePitchUm(SweepSpec spec, BitMask image) => Units.MmToUm(spec.CellMm) / Math.Max(image.Width, image.Height);

    /// <summary>A value as its label burns it: up to three decimals, no trailing zeros.</summary>
    private static string Label(double value) => value.ToString("0.###", CultureInfo.InvariantCulture);

    private static string N(double value) => MachineLimits.Text.N(value);
}
