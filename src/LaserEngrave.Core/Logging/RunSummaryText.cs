using System.Globalization;
using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>The plain-text summary of a run that a person reads and copies into a lab notebook.</summary>
public static class RunSummaryText
{
    /// <summary>The "Laser off" line: which command the gate acknowledged, or that none did and a person must check the laser.</summary>
    public static string LaserOff(RunFault fault)
    {
        ArgumentNullException.ThrowIfNull(fault);
        var confirmed = ConfirmedBy(fault);
        return fault.BurstEnded
            ? $"the burst had ended by itself at the run's end (the gate counts its pulses) before the switch-off was refused or went unanswered; then {confirmed}"
            : confirmed;
    }

    private static string ConfirmedBy(RunFault fault)
    {
        return (fault.LaserOffConfirmed, fault.LaserOffBy) switch
        {
            (true, LaserOffPath.OffAgain) => "confirmed by the gate acknowledging OFF, late or sent again (it had refused or not answered a switch-off in time; FREQ 0, its shortest watchdog and a stage stop went with it)",
            (true, LaserOffPath.FrequencyZero) => "confirmed by the gate acknowledging FREQ 0 (it had refused or not answered a switch-off and OFF again)",
            (true, _) => "confirmed by the gate (it acknowledged OFF)",
            (false, LaserOffPath.None) => "NOT CONFIRMED: the gate acknowledged neither OFF nor FREQ 0; its port was closed so that its watchdog switches the laser off; a person must check the laser",
            _ => "NOT CONFIRMED: the gate did not answer; check the laser by hand",
        };
    }

    /// <summary>
    /// The switchings sent late and the timing doubts the run went on from, in one line ("late switch-ons: 4 within the
    /// 1.5 µm edge tolerance (latest 1.42 µm); went on after 2 timing doubts"), for where a run's outcome is read in a
    /// glance (the app's last run and run history); null when there were none.
    /// </summary>
    public static string? Timing(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var late = LateSwitches(record.LateSwitches, record.Profile.Gate.CountsBursts);
        var wentOn = WentOnAfter(record.Recoveries?.Count ?? 0);
        var timing = (late, wentOn) switch
        {
            (null, null) => null,
            (null, _) => wentOn,
            (_, null) => "late " + late,
            _ => $"late {late}; {wentOn}",
        };
        return GuardScale(record.GuardScale) is { } guards ? (timing is null ? guards : $"{timing}; {guards}") : timing;
    }

    /// <summary>The guards' widening as the summary says it ("guards 2.4 x the profile's latency spread: lines shorter by ..."); null when the profile's held.</summary>
    public static string? GuardScale(double? scale) =>
        scale is > 1 and var s
            ? string.Create(CultureInfo.InvariantCulture, $"guards {s:0.##} x the profile's latency spread (every switching aimed that much further inside its run: lines come out shorter)")
            : null;

    /// <summary>The switchings sent late, as the summary's "Late switches" line says them ("switch-ons: 4 within ..."); null when none.</summary>
    /// <param name="late">The record's late switchings.</param>
    /// <param name="countedBurst">Whether the gate counts its bursts; a frequency-only gate's late switch-offs were stopped in time by their early aim, not by a burst.</param>
    public static string? LateSwitches(LateSwitches? late, bool countedBurst = true)
    {
        if (late is null || (late.Count == 0 && late.LateOffs == 0))
        {
            return null;
        }

        var c = CultureInfo.InvariantCulture;
        var parts = new List<string>(2);
        if (late.Count > 0)
        {
            parts.Add(string.Create(c, $"switch-ons: {late.Count} within the {late.ToleranceUm:0.###} µm edge tolerance (latest {late.LatestUm:0.##} µm)"));
        }

        if (late.LateOffs > 0)
        {
            parts.Add(countedBurst
                ? string.Create(c, $"switch-offs: {late.LateOffs} (the burst had ended the run by itself)")
                : string.Create(c, $"switch-offs: {late.LateOffs} within the {late.ToleranceUm:0.###} µm edge tolerance (each aimed that much early, so the laser stopped before the edge)"));
        }

        return string.Join("; ", parts);
    }

    /// <summary>How many timing doubts the run went on from (each a "Went on after" line of the summary); null when none.</summary>
    /// <summary>How many timing doubts the summary lists one by one before counting the rest in one line.</summary>
    public const int ListedRecoveries = 3;

    public static string? WentOnAfter(int recoveries) =>
        recoveries <= 0 ? null : string.Create(CultureInfo.InvariantCulture, $"went on after {recoveries} timing doubt{(recoveries == 1 ? string.Empty : "s")}");

    /// <summary>The profile's edge tolerance and what it does, as preflight says it (docs/execution.md, "Late switchings").</summary>
    public static string EdgeTolerance(double toleranceUm) =>
        EdgeToleranceInBrief(toleranceUm) + ": a switch-on this computer sends later than that at the burn speed is not sent: that run stays unburned and the run goes on from it, laser off";

    /// <summary>The tolerance in a few words ("edge tolerance 1.5 µm"), where a row has no room for what it means (the app's Machine panel, with <see cref="EdgeTolerance"/> as its tooltip).</summary>
    public static string EdgeToleranceInBrief(double toleranceUm) => string.Create(CultureInfo.InvariantCulture, $"edge tolerance {toleranceUm:0.###} µm");

    public static string Format(RunRecord record)
    {
        ArgumentNullException.ThrowIfNull(record);
        var c = CultureInfo.InvariantCulture;
        var text = new StringBuilder();
        void Line(string label, string value) => text.Append(c, $"{label + ":",-20}{value}").Append('\n');

        text.Append("LaserEngrave run\n");
        Line("Sample", record.SampleId ?? "(none)");
        Line("Outcome", Outcome(record));
        if (record.Fault is { } fault)
        {
            Line("Fault", fault.Message + (fault.Kind is null ? string.Empty : $" ({fault.Kind})"));
            Line("Laser off", LaserOff(fault));
        }

        if (record.StoppedAt is { } stop)
        {
            // In mm first, as the app's panel and cross show the stage; the microsteps after, as the stage counts them.
            var position = stop.XMicrosteps is { } x && stop.YMicrosteps is { } y ? $", {StagePlace(x, y, record.Profile)}" : string.Empty;
            // Counted as the run bar and the "Done" line count (the engine's rows or strokes done), so that they agree; the
            // image row (or stroke) of the move it stopped in follows, as the stop point holds it.
            var (unit, within) = record.Drawing is null ? ("rows", "image row") : ("strokes", "stroke");
            Line("Stopped at", string.Create(c, $"after {record.RowsDone} of {record.RowsTotal} {unit}, move {stop.MoveIndex} ({within} {stop.Row}){position}"));
            if (stop is { ResumeXMicrosteps: { } resumeX, CutPixel: { } cut })
            {
                var check = stop.ExpectedXMicrosteps is { } expected ? string.Create(c, $" if X is found at {expected} microsteps (else from the run's start)") : string.Empty;
                var watchdog = stop.OffByGateWatchdog ? " (the gate's link was lost: the laser went off by the gate's watchdog, which it must report tripped)" : string.Empty;
                Line("Resumes", string.Create(c, $"mid-run at X {resumeX} microsteps{check}; pixel column {cut.Column}, row {cut.Row} (the laser went off in it{watchdog}) burns twice"));
            }
            else if (stop.CutPixel is { } first)
            {
                Line("Resumes", string.Create(c, $"from the run's start; its pixels up to column {first.Column}, row {first.Row} (where the laser went off at the latest, or its switch-on was never acknowledged) may get part of their dose twice"));
            }

            if (stop is { OffByGateWatchdog: true, OffCutPixel: { } offCut })
            {
                Line("Or resumes", stop.OffResumeXMicrosteps is { } offX
                    ? string.Create(c, $"mid-run at X {offX} microsteps if the gate reports its watchdog did not trip (it heard the OFF); then pixel column {offCut.Column}, row {offCut.Row} burns twice")
                    : string.Create(c, $"from the run's start if the gate reports its watchdog did not trip (it heard the OFF); then its pixels up to column {offCut.Column}, row {offCut.Row} may get part of their dose twice"));
            }
        }

        Line("Started", record.StartedAt.ToString("yyyy-MM-dd HH:mm:ss zzz", c));
        Line("Ended", record.EndedAt.ToString("yyyy-MM-dd HH:mm:ss zzz", c));
        var clock = record.Simulated ? " (on the simulator's clock)" : string.Empty;
        Line("Duration", string.Create(c, $"{Duration(record.ActualSeconds)}, estimated {Duration(record.EstimatedSeconds)}{clock}; engraving {Duration(record.EngravingSeconds)}, estimated {Duration(record.EstimatedEngravingSeconds)}"));
        Line("Laser on", Duration(record.LaserOnSeconds));
        Line("Done", record.Drawing is null
            ? string.Create(c, $"{record.RowsDone} of {record.RowsTotal} rows, {record.RunsDone} of {record.RunsTotal} burn runs")
            : string.Create(c, $"{record.RowsDone} of {record.RowsTotal} strokes, {record.RunsDone} of {record.RunsTotal} paths"));
        // A job of layers counts its layers, each with its own passes (listed below); its image and figures here are its
        // first layer's, and say so.
        var layers = record.Layers ?? [];
        var ofFirstLayer = layers.Count > 0 ? " (layer 1)" : string.Empty;
        if (layers.Count > 0)
        {
            Line("Layers", string.Create(c, $"{layers.Count(l => l.Outcome == Jobs.RunOutcome.Completed)} of {layers.Count} completed (each with its passes below)"));
        }
        else if (record.Passes > 1)
        {
            Line("Passes", string.Create(c, $"{record.PassesDone ?? 0} of {record.Passes} done (rows and runs above: the last pass)"));
        }

        var g = record.Geometry;
        if (record.Drawing is { } d)
        {
            Line("Drawing" + ofFirstLayer, record.Image.Path);
            Line("Drawing SHA-256", record.Image.Sha256);
            Line("Size on stage", string.Create(c, $"{g.WidthMm:0.####} x {g.HeightMm:0.####} mm (scale {d.Scale:0.######})"));
            Line("Origin", string.Create(c, $"{g.OriginXMm:0.####}, {g.OriginYMm:0.####} mm"));
            Line("Paths", string.Create(c, $"{d.Paths} ({d.Fill.ToString().ToLowerInvariant()}{(d.Fill == Vectors.VectorFillMode.Outline ? string.Empty : $", fill pitch {d.FillPitchUm:0.##} µm")}), curves within {d.ToleranceUm:0.###} µm, {(d.DrawingOrder ? "drawing order" : "ordered")}"));
            Line("Strokes", string.Create(c, $"{d.Strokes}, burn {d.BurnLengthMm:0.###} mm, travel {d.TravelMm:0.###} mm, model within {d.PredictedDeviationUm:0.##} µm of the path"));
        }
        else
        {
            Line("Image" + ofFirstLayer, string.Create(c, $"{record.Image.Path} ({record.Image.WidthPx} x {record.Image.HeightPx} px)"));
            Line("Image SHA-256", record.Image.Sha256);
            var m = record.Mask;
            Line("Mask", string.Create(c, $"threshold {m.ThresholdPercent:0.##} %, dither {m.Dither.ToString().ToLowerInvariant()}{(m.Invert ? ", inverted" : string.Empty)}"));
            Line("Size on stage", string.Create(c, $"{g.WidthMm:0.####} x {g.HeightMm:0.####} mm (asked: {g.Size.ToSizeSpec().Describe()})"));
            Line("Origin", string.Create(c, $"{g.OriginXMm:0.####}, {g.OriginYMm:0.####} mm"));
            Line("Pitch", string.Create(c, $"{g.PitchUm:0.####} µm = {g.MicrostepsPerPixel:0.####} microsteps per pixel ({g.MicrostepUm} µm per microstep)"));
            var p = record.Plan;
            Line("Strategy", p.Strategy == PlanStrategy.Paper
                ? "paper"
                : string.Create(c, $"optimized, {(p.Bidirectional ? "bidirectional" : "unidirectional")}, overscan {p.OverscanMm:0.###} mm"));
        }

        var s = record.Process;
        Line("Speeds", string.Create(c, $"burn {s.BurnSpeedMmPerS:0.###} mm/s, travel {s.TravelSpeedMmPerS:0.###} mm/s, acceleration {s.AccelerationMmPerS2:0.###} mm/s²"));
        Line("Laser frequency", string.Create(c, $"{s.LaserFrequencyHz:0.###} Hz"));
        Line("Mode", s.Mode == PlanMode.Dots
            ? string.Create(c, $"dots: {s.PulsesPerDot} pulses per dot, a dot {(s.DotPitchMicrosteps == 0 ? "at every pixel's centre" : $"every {s.DotPitchMicrosteps} microsteps")}, settle {s.DotSettleMs:0.###} ms")
            : "raster (burning while moving)");
        Line("Machine", record.Profile.Name + (record.Simulated ? " (simulator)" : string.Empty));
        if (record.NoWatchdogAccepted is { } accepted)
        {
            Line("No watchdog", "accepted before the run: " + accepted);
        }
        if (record.HostPriority is { } priority)
        {
            Line("Host priority", priority);
        }

        if (LateSwitches(record.LateSwitches, record.Profile.Gate.CountsBursts) is { } late)
        {
            Line("Late switches", late);
        }

        if (GuardScale(record.GuardScale) is { } guards)
        {
            Line("Guards", guards);
        }

        // A run can go on after thousands of doubts: the first few are listed, the rest counted (the JSON keeps them all).
        var recoveries = record.Recoveries ?? [];
        foreach (var recovery in recoveries.Take(ListedRecoveries))
        {
            Line("Went on after", string.Create(c, $"pass {recovery.Pass}, row {recovery.Row + 1} (move {recovery.MoveIndex}): {recovery.Fault}"));
        }

        if (recoveries.Count > ListedRecoveries)
        {
            var rest = recoveries.Skip(ListedRecoveries).ToList();
            var first = rest.Min(r => r.Pass);
            var last = rest.Max(r => r.Pass);
            Line("Went on after", string.Create(c, $"{rest.Count} more timing doubts ({(first == last ? $"pass {first}" : $"passes {first}-{last}")}), listed in the JSON record's recoveries"));
        }

        if (recoveries.Count > 0)
        {
            // Each doubt's own sentence says the laser stayed off "for that run": the run was then burned when the job went
            // on from its stop point, which the counts above include. Said once, so the two never read as a contradiction.
            Line("Went on", "each run the laser was kept off for at a doubt was burned when the job went on from there (the counts above are the whole job's)");
        }

        var warnings = record.LineWarnings ?? [];
        foreach (var warning in warnings.Take(ListedRecoveries))
        {
            Line("Line", warning);
        }

        if (warnings.Count > ListedRecoveries)
        {
            Line("Line", string.Create(c, $"{warnings.Count - ListedRecoveries} more, listed in the JSON record's lineWarnings"));
        }

        foreach (var device in record.Devices)
        {
            Line("Device", $"{device.Role} on {device.Port}: {device.Identity}, firmware {device.Firmware}");
        }

        if (record.Simulation is { } sim)
        {
            if (sim.Path is { } path)
            {
                Line("Twin", string.Create(c, $"seed {sim.Seed}, {sim.Pulses} pulses, {path.OffPathPulses} off the path"));
                Line("Path deviation", string.Create(c, $"mean {path.DeviationUm.Mean:0.###} µm, largest {path.DeviationUm.Max:0.###} µm"));
                Line("Pulse spacing", string.Create(c, $"{path.PulseSpacingUm.Min:0.###}..{path.PulseSpacingUm.Max:0.###} µm, mean {path.PulseSpacingUm.Mean:0.####} µm (v/f = {path.ExpectedSpacingUm:0.####} µm)"));
                if (sim.Dwells is { } pathDwells)
                {
                    Line("Dwells", string.Create(c, $"{pathDwells.Count} ({pathDwells.Pulses} pulses with the stage still)"));
                }
            }
            else
            {
                Line("Twin", string.Create(c, $"seed {sim.Seed}, {sim.Pulses} pulses, {sim.MissingPixels} pixels missing, {sim.ExtraPixels} extra, {sim.LaserOnTravelCount} pulses off the black"));
                if (sim.Edges is { } edges)
                {
                    Line("Edges", string.Create(c, $"{edges.Count}: mean error {edges.MeanErrorUm:0.##} µm, largest {edges.MaxErrorUm:0.##} µm"));
                }

                if (sim.PulsesWhileMoving is { } moving)
                {
                    Line("Pulses moving", string.Create(c, $"{moving} fired while the stage moved"));
                }

                if (sim.Dwells is { } dwells)
                {
                    Line("Dwells", string.Create(c, $"{dwells.Count} ({dwells.Pulses} pulses with the stage still)"));
                }

                Line("Pulses per pixel", string.Create(c, $"min {sim.PulsesPerPixel.Min}, mean {sim.PulsesPerPixel.Mean:0.#}, max {sim.PulsesPerPixel.Max}"));
            }
        }

        foreach (var (layer, i) in (record.Layers ?? []).Select((l, i) => (l, i + 1)))
        {
            var ended = LayerEnd(layer);
            var path = layer.Simulation?.Path is { } figures ? string.Create(c, $"; twin: deviation max {figures.DeviationUm.Max:0.##} µm, spacing {figures.PulseSpacingUm.Min:0.###}..{figures.PulseSpacingUm.Max:0.###} µm") : string.Empty;
            Line($"Layer {i}", string.Create(
                c,
                $"\"{layer.Name}\" {layer.Mode.ToString().ToLowerInvariant()} {Path.GetFileName(layer.Source)}{(layer.DrawingLayer is null ? string.Empty : $" layer {layer.DrawingLayer}")}: {layer.BurnSpeedMmPerS:0.###} mm/s, {layer.FrequencyHz:0.###} Hz, {layer.PassesDone} of {layer.Passes} passes, {ended}, engraving {Duration(layer.EngravingSeconds)} (estimated {Duration(layer.EstimatedEngravingSeconds)}){path}"));
        }

        if (record.RepeatOf is { } repeated)
        {
            Line(record.Resumed ? "Resumes" : "Repeats", repeated + (record.Resumed ? " (from where it stopped)" : string.Empty));
        }

        Line("Software", "LaserEngrave " + record.SoftwareVersion);
        Line("Notes", string.IsNullOrWhiteSpace(record.Notes) ? "(none)" : record.Notes.ReplaceLineEndings("\n" + new string(' ', 20)));
        return text.ToString();
    }

    /// <summary>A duration as "1 h 02 min 03 s" or "2 min 03.4 s".</summary>
    /// <summary>How a layer of a run ended, in a word or three: "completed", "failed", "not started", "completed before" (by the run resumed).</summary>
    public static string LayerEnd(RunLayer layer)
    {
        ArgumentNullException.ThrowIfNull(layer);
        return layer.CompletedBefore ? "completed before (by the run resumed)"
            : layer.Outcome is { } outcome ? outcome.ToString().ToLowerInvariant()
            : "not started";
    }

    public static string Duration(double seconds)
    {
        var c = CultureInfo.InvariantCulture;
        if (!double.IsFinite(seconds) || seconds < 0)
        {
            return "unknown";
        }

        var t = TimeSpan.FromSeconds(Math.Round(seconds, 1));
        return t.TotalHours >= 1
            ? string.Create(c, $"{(int)t.TotalHours} h {t.Minutes:00} min {t.Seconds:00} s")
            : string.Create(c, $"{t.Minutes} min {t.Seconds + Units.MsToSeconds(t.Milliseconds):00.0} s");
    }

    private static string Outcome(RunRecord record) => record.Outcome switch
    {
        RunOutcome.Completed => "completed",
        RunOutcome.Aborted => "aborted by the operator",
        RunOutcome.Failed => "FAILED",
        RunOutcome.Refused => "refused before starting",
        _ => record.Outcome.ToString(),
    };

    /// <summary>
    /// Where the stage stopped, in the words the log's <c>Stopped at</c> line and the app's run bar share: in mm first, as the
    /// app shows the stage, then the microsteps the stage counts ("stage at X 19.332 mm, Y 6.707 mm (194843, 67602 microsteps)").
    /// </summary>
    public static string StagePlace(long xMicrosteps, long yMicrosteps, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        return string.Create(CultureInfo.InvariantCulture, $"stage at X {StageUnits.MicrostepsToMm(xMicrosteps, profile.X.MicrostepUm):0.###} mm, Y {StageUnits.MicrostepsToMm(yMicrosteps, profile.Y.MicrostepUm):0.###} mm ({xMicrosteps}, {yMicrosteps} microsteps)");
    }
}
