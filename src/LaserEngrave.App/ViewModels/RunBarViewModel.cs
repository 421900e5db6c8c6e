using CommunityToolkit.Mvvm.Input;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// The run bar's one Start, one Abort and one progress: the sweep while the stage shows it (or while it runs), else the
/// job or its layers. The choice the bar once made in its markup, here so that it is tested and the bar only renders it.
/// </summary>
public sealed class RunBarViewModel
{
    private readonly RunViewModel _run;
    private readonly SweepViewModel? _sweep;

    /// <param name="sweep">The sweep, when the page has one; without it the bar runs the job alone.</param>
    public RunBarViewModel(RunViewModel run, SweepViewModel? sweep = null)
    {
        ArgumentNullException.ThrowIfNull(run);
        _run = run;
        _sweep = sweep;
    }

    /// <summary>Whether this bar is over these two (a component keeps one while its parameters stay).</summary>
    public bool Is(RunViewModel run, SweepViewModel? sweep) => ReferenceEquals(_run, run) && ReferenceEquals(_sweep, sweep);

    /// <summary>A sweep runs: the bar shows its cells, and Abort aborts it.</summary>
    public bool Sweeping => _sweep is { IsRunning: true };

    /// <summary>Start runs the sweep shown on the stage (the Sweep panel's "Show the sweep on the stage"), unless a run is under way.</summary>
    public bool RunsSweep => _sweep is { ShowsOnStage: true } && !_run.IsActive;

    /// <summary>What Start starts: the sweep shown on the stage, else the job (or its layers).</summary>
    public IAsyncRelayCommand StartCommand => RunsSweep ? _sweep!.RunSweepCommand : _run.StartCommand;

    /// <summary>How far what runs has come, 0..1.</summary>
    public double Fraction => Sweeping ? _sweep!.Fraction : _run.Fraction;

    /// <summary>Whether Abort has something to stop.</summary>
    public bool CanAbort => Sweeping || _run.IsActive;

    /// <summary>Stops what runs: the sweep when one runs, else the run (always allowed, laser off first).</summary>
    public void Abort()
    {
        if (Sweeping && _sweep!.AbortSweepCommand.CanExecute(null))
        {
            _sweep.AbortSweepCommand.Execute(null);
            return;
        }

        _run.AbortCommand.Execute(null);
    }
}
