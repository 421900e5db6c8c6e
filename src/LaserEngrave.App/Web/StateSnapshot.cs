using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Machines.Runs;

namespace LaserEngrave.App.Web;

/// <summary>The page's whole view of the app at one moment, as JSON; sent on request and over the event stream.</summary>
internal static class StateSnapshot
{
    public static object From(MainViewModel main)
    {
        var job = main.Job;
        var machine = main.Machine;
        var run = main.Run;
        var log = main.Log;
        var info = job.ImageInfo;
        // Every kind of job has an estimate: the figures all kinds answer from the job, an image's own (moves, lengths, scale) beside them.
        var engraving = job.Engraving;
        var stats = job.Job?.Statistics;
        var geometry = job.Job?.Geometry;
        var progress = run.Progress;

        // Read once: the panel's words and the run's laserOn come from this one value, so they cannot disagree.
        var laser = machine.Laser;
        return new
        {
            settings = new { theme = main.Settings.Theme, recentFiles = main.Settings.RecentFiles, lastFolder = main.Settings.LastFolder },
            activity = new
            {
                busy = main.Activity.IsBusy,
                operation = main.Activity.Current?.Kind.ToString(),
                message = main.Activity.BusyMessage,
            },
            samples = main.SampleImages,
            profileError = main.ProfileError,
            settingsError = main.SettingsError,
            image = new
            {
                path = job.ImagePath,
                name = job.ImagePath is null ? null : Path.GetFileName(job.ImagePath),
                info = info is null ? null : new
                {
                    format = info.Format.ToString(),
                    info.Width,
                    info.Height,
                    info.BitsPerPixel,
                    info.PaletteSize,
                    info.FileSizeBytes,
                    info.DpiX,
                    info.DpiY,
                    info.Compression,
                    info.HasAlpha,
                },
                maskVersion = job.MaskVersion,
                burnPixels = job.Mask?.CountSet(),
                loading = job.LoadingLine,
            },
            job = new
            {
                job.ThresholdPercent,
                dither = job.Dither.ToString(),
                job.Invert,
                job.QuarterTurns,
                job.MirrorX,
                job.MirrorY,
                sizeMode = job.SizeMode.ToString(),
                job.AspectLocked,
                job.WidthMm,
                job.HeightMm,
                job.PitchUm,
                job.MicrostepsPerPixel,
                job.OriginXMm,
                job.OriginYMm,
                job.LaserFrequencyHz,
                job.BurnSpeedMmPerS,
                job.TravelSpeedMmPerS,
                job.AccelerationMmPerS2,
                strategy = job.Strategy.ToString(),
                job.Bidirectional,
                job.OverscanMm,
                job.Passes,
                mode = job.Mode.ToString(),
                job.PulsesPerDot,
                job.DotPitchMicrosteps,
                job.DotSettleMs,
                job.PulseEnergyUj,
                pulses = job.PulsesSummary,
                errors = job.Errors,
                warnings = job.Warnings,
                planVersion = job.PlanVersion,
                lockedBecause = job.LockedBecause,
            },
            estimate = engraving is null ? null : new
            {
                seconds = job.EstimatedSeconds,
                rows = engraving.Planned.Units,
                moves = stats?.Moves,
                burnRuns = engraving.Planned.Runs,
                burnLengthMm = stats?.BurnLengthMm,
                travelLengthMm = stats?.TravelLengthMm,
                achievedWidthMm = engraving.Parts[0].SizeMm.WidthMm,
                achievedHeightMm = engraving.Parts[0].SizeMm.HeightMm,
                residualScaleError = geometry?.ResidualScaleError,
                engraving.FitsTravel,
                unit = engraving.UnitOf(1),
                startProblem = EngraveRun.Unrunnable(engraving),
            },
            machine = new
            {
                machine.UseSimulator,
                machine.StagePort,
                machine.LaserPort,
                machine.Ports,
                connected = machine.IsConnected,
                description = machine.Connection?.Description,
                profile = machine.Profile.Name,
                travelXMm = machine.Profile.X.TravelMm,
                travelYMm = machine.Profile.Y.TravelMm,
                microstepUm = machine.Profile.X.MicrostepUm,
                machine.Identity,
                machine.XMicrosteps,
                machine.YMicrosteps,
                xMm = machine.XMicrosteps is { } x ? StageUnits.MicrostepsToMm(x, machine.Profile.X.MicrostepUm) : (double?)null,
                yMm = machine.YMicrosteps is { } y ? StageUnits.MicrostepsToMm(y, machine.Profile.Y.MicrostepUm) : (double?)null,
                machine.XHomed,
                machine.YHomed,
                gateState = laser is null ? null : MachineViewModel.Describe(laser),
                machine.IsBusy,
                machine.Error,
            },
            testMoves = new
            {
                main.TestMoves.StepUm,
                stepChoicesUm = TestMovesViewModel.StepChoicesUm,
                main.TestMoves.GoToXMm,
                main.TestMoves.GoToYMm,
                main.TestMoves.TestFirePulses,
                main.TestMoves.Error,
            },
            run = new
            {
                state = run.Bar.StateName,
                engineState = run.State.ToString(),
                active = run.IsActive,
                run.RunPlanVersion,
                movesDone = progress?.MovesDone,
                movesTotal = progress?.MovesTotal,
                rowsDone = progress?.Run.RowsDone,
                rowsTotal = progress?.Run.RowsTotal,
                pass = progress?.PassInLayer.Pass,
                passes = progress?.PassInLayer.Passes,
                layer = run.Bar.LayerCount is null ? null : progress?.Layer,
                layers = run.Bar.LayerCount,
                pauseRequested = progress?.PauseRequested,
                // Where the engine's timing puts the stage now (the drawn cross: planned positions between its reports),
                // the instant on the machine's clock it stands for, and the engine's last report itself.
                x = run.PacedLaser?.X ?? progress?.Run.XMicrosteps,
                y = run.PacedLaser?.Y ?? progress?.Run.YMicrosteps,
                atSeconds = run.PacedLaser is { } paced ? Math.Round(paced.AtSeconds, 4) : (double?)null,
                reportedX = progress?.Run.XMicrosteps,
                reportedY = progress?.Run.YMicrosteps,
                laserOn = progress is null ? (bool?)null : run.IsActive && laser is not null ? laser.Firing : progress.Run.LaserOn,
                phase = progress is null ? null : run.State.ToString().ToLowerInvariant(),
                percent = Math.Round(run.Fraction * 100, 1),
                elapsedSeconds = Math.Round(run.Bar.ElapsedSeconds, 1),
                remainingSeconds = Math.Round(run.RemainingSeconds, 1),
                run.Error,
                run.Notice,
                canContinue = run.CanContinue,
                run.ContinueUnavailableReason,
                stoppedAtRow = run.StoppedAt?.Row,
            },
            log = new
            {
                log.Notes,
                log.SampleId,
                log.Folder,
                lastRun = log.LastRun is null ? null : Summary(log.LastRun),
                history = log.History.Take(50).Select(Summary),
                log.Error,
                log.Notice,
            },
        };
    }

    private static object Summary(RunLogEntry entry)
    {
        var r = entry.Record;
        return new
        {
            path = entry.Path,
            startedAt = r?.StartedAt,
            outcome = r?.Outcome.ToString().ToLowerInvariant() ?? "unreadable",
            sampleId = r?.SampleId,
            notes = r?.Notes,
            error = r?.Fault?.Message ?? entry.Error,
            image = r is null ? null : Path.GetFileName(r.Image.Path),
            actualSeconds = r is null ? 0 : Math.Round(r.ActualSeconds, 1),
            simulated = r?.Simulated,
            text = r is null ? entry.Error : RunSummaryText.Format(r),
        };
    }
}
