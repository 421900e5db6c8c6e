using System.Diagnostics;
using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Cli.Commands;

/// <summary>Shows a run's progress: a redrawn bar (rows, percent, ETA) on a terminal, a plain line every 10 % when redirected.</summary>
/// <remarks>Called after every move on the run's thread, so it only prints when something visible changed or time passed.</remarks>
internal sealed class ProgressPrinter(TextWriter writer, bool terminal) : IProgress<EngraveProgress>
{
    private const int BarWidth = 30;
    private static readonly TimeSpan RedrawInterval = TimeSpan.FromMilliseconds(100);
    private static readonly TimeSpan PlainInterval = TimeSpan.FromSeconds(30);

    private readonly Stopwatch _sinceLastPrint = Stopwatch.StartNew();
    private int _lastDecile = -1;
    private RunState? _lastState;
    private bool _barShown;
    private string? _pass;
    private bool _drawing;

    // The rows done when the run was last seen moving, and the recoveries already said (the session counts them).
    private int _rowsDoneUnderWay;
    private int _recoveriesSaid;

    /// <summary>
    /// The job that runs: a drawing's rows are strokes and its burn runs paths (<see cref="EngraveJob.UnitOf"/>), and a
    /// job of layers names the layer under way; null shows rows.
    /// </summary>
    public EngraveJob? Job { get; init; }

    /// <summary>A session's progress: its pass's figures under the session's state (a pass's end is not the run's).</summary>
    public void Report(EngraveProgress value)
    {
        ArgumentNullException.ThrowIfNull(value);
        // The pass within its layer: a job of ten one-pass layers is "1 of 1, layer 3 of 10", not pass 3 of 10.
        var (pass, passes) = value.PassInLayer;
        _pass = passes > 1 ? string.Create(CultureInfo.InvariantCulture, $"{pass} of {passes}") : null;
        if (Job?.Layers is { Count: > 0 } layers && value.Layer >= 1 && value.Layer <= layers.Count)
        {
            _pass = string.Create(CultureInfo.InvariantCulture, $"{_pass ?? "1 of 1"}, layer {value.Layer} of {layers.Count} \"{layers[value.Layer - 1].Layer.Name}\"");
        }

        _drawing = Job?.UnitOf(value.Layer) == JobPart.StrokeUnit;
        if (value is { State: RunState.Preflight, Recovering: true })
        {
            // Said once per recovery; the preflight's own figures (a fresh count, 0 %) would only make the bar jump back.
            if (value.Recoveries != _recoveriesSaid)
            {
                _recoveriesSaid = value.Recoveries;
                if (value.Recoveries > RunSummaryText.ListedRecoveries)
                {
                    // Hundreds of the same lines (this one and the "running" after it) would bury the run's end: the
                    // rest are counted in one line when the run ends.
                    return;
                }

                _lastState = RunState.Preflight;
                var total = Math.Max(1, value.Run.RowsTotal);
                var row = Math.Min(_rowsDoneUnderWay + 1, total);
                Print(() =>
                {
                    if (_barShown)
                    {
                        writer.WriteLine();
                        _barShown = false;
                    }

                    writer.WriteLine(Recovering(row, total, _pass, _drawing));
                    writer.Flush();
                });
                _sinceLastPrint.Restart();
            }

            return;
        }

        if (value.State != RunState.Preflight)
        {
            _rowsDoneUnderWay = value.Run.RowsDone;
        }

        Report(value.Run with { State = value.State });
    }

    public void Report(RunProgress progress)
    {
        ArgumentNullException.ThrowIfNull(progress);
        var stateChanged = progress.State != _lastState;
        _lastState = progress.State;
        if (terminal)
        {
            if (stateChanged || _sinceLastPrint.Elapsed >= RedrawInterval)
            {
                Print(() =>
                {
                    writer.Write("\r" + Bar(progress, _pass, _drawing));
                    writer.Flush();
                });
                _barShown = true;
                _sinceLastPrint.Restart();
            }

            return;
        }

        var decile = (int)Math.Floor(Math.Clamp(progress.Percent, 0, 100) / 10);
        if (decile != _lastDecile || stateChanged || _sinceLastPrint.Elapsed >= PlainInterval)
        {
            _lastDecile = decile;
            Print(() => writer.WriteLine(Line(progress, _pass, _drawing)));
            _sinceLastPrint.Restart();
        }
    }

    /// <summary>Ends the bar's line so what follows starts on a fresh one.</summary>
    public void Finish()
    {
        if (_barShown)
        {
            Print(writer.WriteLine);
            _barShown = false;
        }

        if (_recoveriesSaid > RunSummaryText.ListedRecoveries)
        {
            var more = _recoveriesSaid - RunSummaryText.ListedRecoveries;
            Print(() => writer.WriteLine(string.Create(CultureInfo.InvariantCulture, $"recovering: went on after {more} more timing doubt{(more == 1 ? string.Empty : "s")} ({_recoveriesSaid} in all; the run log lists each)")));
        }
    }

    // A terminal hung up (SIGHUP) fails every write: the run's abort, laser off first, must not fail with it.
    private static void Print(Action write)
    {
        try
        {
            write();
        }
        catch (IOException)
        {
            // Nobody is left to read the progress; the run log says how it ended.
        }
    }

    /// <param name="p">The pass's progress.</param>
    /// <param name="pass">"1 of 2" when the job has several passes.</param>
    /// <param name="drawing">A drawing's run: strokes and paths instead of rows and burn runs.</param>
    internal static string Bar(RunProgress p, string? pass = null, bool drawing = false)
    {
        var filled = (int)Math.Round(Math.Clamp(p.Percent, 0, 100) / 100 * BarWidth);
        var state = p.State is RunState.Running ? string.Empty : $"  {StateLabel(p)}";
        return string.Create(
            CultureInfo.InvariantCulture,
            $"[{new string('#', filled)}{new string('.', BarWidth - filled)}] {p.Percent,5:0.0} %  {(drawing ? "stroke" : "row")} {p.RowsDone}/{p.RowsTotal}{(pass is null ? string.Empty : $"  pass {pass}")}  ETA {Eta(p)}{state}   ");
    }

    internal static string Line(RunProgress p, string? pass = null, bool drawing = false) => p.State == RunState.Preflight
        ? "preflight: checking the machine and the job" + (pass is null ? string.Empty : $" (pass {pass})")
        : string.Create(
            CultureInfo.InvariantCulture,
            $"{StateLabel(p)}: {p.Percent:0} %, {(drawing ? "stroke" : "row")} {p.RowsDone} of {p.RowsTotal}, {p.RunsDone} of {p.RunsTotal} {(drawing ? "paths" : "burn runs")}{(pass is null ? string.Empty : $", pass {pass}")}, {Eta(p)} left");

    /// <summary>The session going on after a timing doubt, as the technician reads it: what happened, what it does now, and from where.</summary>
    /// <param name="row">The row under way (a drawing's stroke), from 1, counted as the progress counts them (rows with something to burn).</param>
    /// <param name="rows">The rows the progress counts.</param>
    /// <param name="pass">"1 of 2" when the job has several passes.</param>
    /// <param name="drawing">A drawing's run: strokes instead of rows.</param>
    internal static string Recovering(int row, int rows, string? pass = null, bool drawing = false) => string.Create(
        CultureInfo.InvariantCulture,
        $"recovering: the run fell behind its timing, laser off; checking the machine again, then going on from {(drawing ? "stroke" : "row")} {row} of {rows}{(pass is null ? string.Empty : $", pass {pass}")}");

    /// <summary>The state as the operator reads it: "done" only when every run was burned, "stopped" for an aborted or failed run.</summary>
    internal static string StateLabel(RunProgress p) => p.State switch
    {
        RunState.Completed when p.RunsDone == p.RunsTotal => "done",
        RunState.Completed or RunState.Aborted or RunState.Failed => "stopped",
        _ => p.State.ToString().ToLowerInvariant(),
    };

    private static string Eta(RunProgress p) => RunSummaryText.Duration(p.Remaining.TotalSeconds);
}
