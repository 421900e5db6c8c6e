using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Test moves view: jog, go to, go to the job's origin, trace its frame, fire a test burst, home.</summary>
/// <remarks>The moves are the Devices <see cref="StageTestMoves"/> (laser off, travel checked); none is allowed while a run is under way.</remarks>
public sealed partial class TestMovesViewModel : ObservableObject
{
    /// <summary>The jog step sizes offered, µm: 1 µm to 10 mm.</summary>
    public static IReadOnlyList<double> StepChoicesUm { get; } = [1, 10, 100, 1000, 10000];

    private readonly MachineViewModel _machine;
    private readonly JobViewModel _job;

    public TestMovesViewModel(MachineViewModel machine, JobViewModel job)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(job);
        _machine = machine;
        _job = job;
        _machine.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(MachineViewModel.Connection) or nameof(MachineViewModel.IsBusy))
            {
                RefreshCommands();
            }
        };
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(JobViewModel.Job))
            {
                RefreshCommands();
            }
        };
    }

    /// <summary>A machine, nothing else moving it, no run.</summary>
    public bool CanMove => !RunActive && _machine.CanUseMachine;

    /// <summary>As <see cref="CanMove"/>, with a planned job to go to or trace.</summary>
    public bool CanMoveToJob => CanMove && _job.Job is not null;

    /// <summary>A move, homing or connect is under way and can be stopped.</summary>
    public bool CanStop => _machine.IsBusy;

    [ObservableProperty]
    public partial double StepUm { get; set; } = 100;

    [ObservableProperty]
    public partial double GoToXMm { get; set; }

    [ObservableProperty]
    public partial double GoToYMm { get; set; }

    [ObservableProperty]
    public partial int TestFirePulses { get; set; } = 100;

    /// <summary>Set by the run view-model while a run owns the machine.</summary>
    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(JogCommand), nameof(GoToCommand), nameof(GoToOriginCommand), nameof(FrameCommand), nameof(TestFireCommand))]
    public partial bool RunActive { get; set; }

    /// <summary>The last failure of a test move, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    /// <summary>Moves one axis by the step size; direction is "x+", "x-", "y+" or "y-".</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanMove))]
    private Task JogAsync(string direction, CancellationToken cancellationToken) => Move((moves, ct) =>
    {
        var (axis, sign) = direction switch
        {
            "x+" => (StageAxisName.X, 1),
            "x-" => (StageAxisName.X, -1),
            "y+" => (StageAxisName.Y, 1),
            "y-" => (StageAxisName.Y, -1),
            _ => throw new ArgumentException($"jog direction '{direction}' is not one of x+, x-, y+, y-"),
        };
        if (!(StepUm > 0) || StepUm > 60000)
        {
            throw new ArgumentException($"step {N(StepUm)} µm must be above 0 and at most 60000 µm");
        }

        return moves.JogAsync(axis, sign * StepUm, ct);
    }, cancellationToken);

    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanMove))]
    private Task GoToAsync(CancellationToken cancellationToken) => Move((moves, ct) => moves.GoToAsync(GoToXMm, GoToYMm, ct), cancellationToken);

    /// <summary>Moves to the job's top-left corner, where the first pixel edge lies.</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanMoveToJob))]
    private Task GoToOriginAsync(CancellationToken cancellationToken) =>
        Move((moves, ct) => moves.GoToOriginAsync(RequireJob().Geometry.Geometry, ct), cancellationToken);

    /// <summary>Traces the job's outline with the laser off, so the user sees where it will land.</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanMoveToJob))]
    private Task FrameAsync(CancellationToken cancellationToken) =>
        Move((moves, ct) => moves.FrameAsync(RequireJob().Geometry.Geometry, visibleFrequencyHz: null, ct), cancellationToken);

    /// <summary>Fires a burst where the stage stands (the stage does not move), at the job's frequency.</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanMove))]
    private Task TestFireAsync(CancellationToken cancellationToken) => Run(async (moves, ct) =>
    {
        if (TestFirePulses is < 1 or > 100000)
        {
            throw new ArgumentException($"test fire of {TestFirePulses} pulses must be 1 to 100000 pulses");
        }

        var frequency = (int)Math.Round(_job.LaserFrequencyHz, MidpointRounding.AwayFromZero);
        if (frequency < 1)
        {
            throw new ArgumentException($"laser frequency {N(_job.LaserFrequencyHz)} Hz must be at least 1 Hz");
        }

        await moves.FirePulsesAsync(TestFirePulses, frequency, ct).ConfigureAwait(false);
        _machine.GateState = MachineViewModel.Describe(await moves.Gate.GetStateAsync(ct).ConfigureAwait(false));
    }, cancellationToken);

    /// <summary>Stops whichever test move or homing is under way.</summary>
    [RelayCommand(CanExecute = nameof(CanStop))]
    private void Stop()
    {
        foreach (var cancel in new[] { JogCancelCommand, GoToCancelCommand, GoToOriginCancelCommand, FrameCancelCommand, TestFireCancelCommand, _machine.HomeCancelCommand, _machine.IdentifyCancelCommand, _machine.ConnectCancelCommand })
        {
            cancel.Execute(null);
        }
    }

    private void RefreshCommands()
    {
        JogCommand.NotifyCanExecuteChanged();
        GoToCommand.NotifyCanExecuteChanged();
        GoToOriginCommand.NotifyCanExecuteChanged();
        FrameCommand.NotifyCanExecuteChanged();
        TestFireCommand.NotifyCanExecuteChanged();
        StopCommand.NotifyCanExecuteChanged();
    }

    private Core.Jobs.PreparedJob RequireJob() =>
        _job.Job ?? throw new ArgumentException("no job planned: open an image and give it a usable size first");

    /// <summary>A move (the Devices test moves switch the laser off first); the positions are read afterwards.</summary>
    private Task Move(Func<StageTestMoves, CancellationToken, Task<StagePosition>> move, CancellationToken cancellationToken) => Run(async (moves, ct) =>
    {
        try
        {
            await move(moves, ct).ConfigureAwait(false);
        }
        finally
        {
            await _machine.ReadPositionsAsync(CancellationToken.None).ConfigureAwait(false);
        }
    }, cancellationToken);

    private async Task Run(Func<StageTestMoves, CancellationToken, Task> action, CancellationToken cancellationToken)
    {
        Error = null;
        if (RunActive)
        {
            Error = "a run is under way: pause or abort it first";
            return;
        }

        await _machine.Guard(async () =>
        {
            var connection = _machine.RequireConnection();
            var moves = new StageTestMoves(connection.Stage, connection.Gate, connection.Profile, timeProvider: connection.TimeProvider);
            await action(moves, cancellationToken).ConfigureAwait(false);
        }).ConfigureAwait(false);
        Error = _machine.Error;
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
