using System.Diagnostics;
using System.Globalization;
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

    /// <summary>A session's progress: its pass's figures under the session's state (a pass's end is not the run's).</summary>
    public void Report(EngraveProgress value)
    {
        ArgumentNullException.ThrowIfNull(value);
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
                writer.Write("\r" + Bar(progress));
                writer.Flush();
                _barShown = true;
                _sinceLastPrint.Restart();
            }

            return;
        }

        var decile = (int)Math.Floor(Math.Clamp(progress.Percent, 0, 100) / 10);
        if (decile != _lastDecile || stateChanged || _sinceLastPrint.Elapsed >= PlainInterval)
        {
            _lastDecile = decile;
            writer.WriteLine(Line(progress));
            _sinceLastPrint.Restart();
        }
    }

    /// <summary>Ends the bar's line so what follows starts on a fresh one.</summary>
    public void Finish()
    {
        if (_barShown)
        {
            writer.WriteLine();
            _barShown = false;
        }
    }

    internal static string Bar(RunProgress p)
    {
        var filled = (int)Math.Round(Math.Clamp(p.Percent, 0, 100) / 100 * BarWidth);
        var state = p.State is RunState.Running ? string.Empty : $"  {StateLabel(p)}";
        return string.Create(
            CultureInfo.InvariantCulture,
            $"[{new string('#', filled)}{new string('.', BarWidth - filled)}] {p.Percent,5:0.0} %  row {p.RowsDone}/{p.RowsTotal}  ETA {Eta(p)}{state}   ");
    }

    internal static string Line(RunProgress p) => p.State == RunState.Preflight
        ? "preflight: checking the machine and the job"
        : string.Create(
            CultureInfo.InvariantCulture,
            $"{StateLabel(p)}: {p.Percent:0} %, row {p.RowsDone} of {p.RowsTotal}, {p.RunsDone} of {p.RunsTotal} burn runs, {Eta(p)} left");

    /// <summary>The state as the operator reads it: "done" only when every run was burned, "stopped" for an aborted or failed run.</summary>
    internal static string StateLabel(RunProgress p) => p.State switch
    {
        RunState.Completed when p.RunsDone == p.RunsTotal => "done",
        RunState.Completed or RunState.Aborted or RunState.Failed => "stopped",
        _ => p.State.ToString().ToLowerInvariant(),
    };

    private static string Eta(RunProgress p) => RunSummaryText.Duration(p.Remaining.TotalSeconds);
}
