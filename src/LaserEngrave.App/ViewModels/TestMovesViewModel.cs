using System.Globalization;
using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Test moves view: jog, go to, go to the job's origin, trace its frame, fire a test burst, home.</summary>
/// <remarks>
/// The moves are the Devices <see cref="StageTestMoves"/> (laser off, travel checked). Each holds the machine through
/// <see cref="MachineActivity"/>, so none is allowed while a run, homing or another move is under way; jog presses
/// during a jog add their step to its target instead.
/// </remarks>
public sealed partial class TestMovesViewModel : ObservableObject
{
    /// <summary>The jog step sizes offered, µm: 1 µm to 10 mm.</summary>
    public static IReadOnlyList<double> StepChoicesUm { get; } = [1, 10, 100, 1000, 10000];

    private readonly MachineViewModel _machine;
    private readonly IJobSession _job;
    private readonly Lock _jogLock = new();

    // The jog under way: the steps pressed so far (µm from where the jog began) and the task that carries them out.
    private double _jogXUm;
    private double _jogYUm;
    private Task? _jogging;

    public TestMovesViewModel(MachineViewModel machine, IJobSession job)
    {
        ArgumentNullException.ThrowIfNull(machine);
        ArgumentNullException.ThrowIfNull(job);
        _machine = machine;
        _job = job;
        machine.Activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                RefreshCommands();
                OnPropertyChanged(nameof(MotionText));
            }
        };
        _machine.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(MachineViewModel.Connection))
            {
                RefreshCommands();
            }
        };
        _job.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName is nameof(IJobSession.PlanVersion))
            {
                RefreshCommands();
                OnPropertyChanged(nameof(JobMoveUnavailableReason));
            }
        };
    }

    [ObservableProperty]
    public partial double StepUm { get; set; } = 100;

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(GoToProblem))]
    public partial double GoToXMm { get; set; }

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(GoToProblem))]
    public partial double GoToYMm { get; set; }

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(TestFireProblem))]
    public partial int TestFirePulses { get; set; } = 100;

    /// <summary>The last failure of a test move, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; private set; }

    private MachineActivity Activity => _machine.Activity;

    /// <summary>
    /// Adds one step to the jog target; direction is "x+", "x-", "y+" or "y-". A press while the stage is still moving
    /// for earlier presses is never lost: the stage goes on to the sum of all the steps, rounded once.
    /// </summary>
    /// <returns>Completes when the stage has reached a target that includes this press (or the jog failed).</returns>
    [RelayCommand(AllowConcurrentExecutions = true, CanExecute = nameof(CanJog))]
    private Task JogAsync(string direction)
    {
        if (JogProblem(direction) is { } problem)
        {
            Error = problem;
            return Task.CompletedTask;
        }

        var (dx, dy) = Direction(direction);
        var step = StepUm;

        lock (_jogLock)
        {
            if (_jogging is null)
            {
                if (!Activity.TryBegin(MachineOperation.Jog, out var lease, out var refusal))
                {
                    Error = refusal;
                    return Task.CompletedTask;
                }

                Error = null;
                _jogXUm = dx * step;
                _jogYUm = dy * step;
                // Where the machine's clock says: on the simulation's loop in virtual time.
                _jogging = TaskRunner.Run(_machine.Connection?.TimeProvider ?? TimeProvider.System, () => JogUntilReachedAsync(lease));
            }
            else
            {
                _jogXUm += dx * step;
                _jogYUm += dy * step;
            }

            return _jogging;
        }
    }

    /// <summary>
    /// Why a jog in <paramref name="direction"/> by <see cref="StepUm"/> is refused, in the job rules' words (the step up to
    /// that axis' travel, as the command line's jog); null when it may be made. The page and the API say it before anything moves.
    /// </summary>
    public string? JogProblem(string? direction)
    {
        var (dx, dy) = Direction(direction);
        if ((dx, dy) == (0, 0))
        {
            return $"jog direction '{direction}' is not one of x+, x-, y+, y-";
        }

        var axis = dx != 0 ? _machine.Profile.X : _machine.Profile.Y;
        return JobRules.JogStep((dx + dy) * StepUm, axis.TravelMm, dx != 0 ? "X" : "Y") is { } rule ? $"step {N(StepUm)} µm: {rule}" : null;
    }

    /// <summary>Why a test fire of <see cref="TestFirePulses"/> is refused, in the job rules' words (as the command line's fire and the devices); null when it may fire.</summary>
    public string? TestFireProblem => JobRules.TestFirePulses(TestFirePulses) is { } rule ? $"test fire of {TestFirePulses} pulses: {rule}" : null;

    private static (int Dx, int Dy) Direction(string? direction) => direction switch
    {
        "x+" => (1, 0),
        "x-" => (-1, 0),
        "y+" => (0, 1),
        "y-" => (0, -1),
        _ => (0, 0),
    };

    /// <summary>A machine, and nothing but a jog holding it (presses during a jog add to its target).</summary>
    private bool CanJog(string? direction) => (!Activity.IsBusy || Activity.Current?.Kind == MachineOperationKind.Jog) && _machine.IsConnected;

    /// <summary>Moves to where the jog began plus every step pressed so far, again as long as presses keep coming.</summary>
    private async Task JogUntilReachedAsync(MachineActivity.Lease lease)
    {
        // Let the press that started the jog return to its caller before the first await on a port.
        await Task.Yield();
        var ended = false;
        try
        {
            var connection = _machine.RequireConnection();
            var moves = new StageTestMoves(connection.Stage, connection.Gate, connection.Profile, timeProvider: connection.TimeProvider);
            var start = await moves.GetPositionAsync(lease.CancellationToken);
            var startXMm = StageUnits.MicrostepsToMm(start.XMicrosteps, connection.Profile.X.MicrostepUm);
            var startYMm = StageUnits.MicrostepsToMm(start.YMicrosteps, connection.Profile.Y.MicrostepUm);
            (double X, double Y) done = (0, 0);
            while (true)
            {
                (double X, double Y) target;
                lock (_jogLock)
                {
                    target = (_jogXUm, _jogYUm);
                    if (target == done)
                    {
                        _jogging = null;
                        lease.Dispose();
                        ended = true;
                        break;
                    }
                }

                try
                {
                    await _machine.FollowAsync(moves.GoToAsync(startXMm + Units.UmToMm(target.X), startYMm + Units.UmToMm(target.Y), lease.CancellationToken), lease.CancellationToken);
                }
                finally
                {
                    await _machine.ReadPositionsAsync(CancellationToken.None);
                }

                done = target;
            }
        }
        catch (OperationCanceledException)
        {
            Error = "cancelled";
        }
        catch (Exception ex) when (ex is Devices.Abstractions.DeviceException or IOException or UnauthorizedAccessException or InvalidOperationException or ArgumentException or TimeoutException)
        {
            Error = ex.Message;
        }
        finally
        {
            if (!ended)
            {
                // A failed jog drops the presses not yet carried out: the user sees where the stage is and presses again.
                lock (_jogLock)
                {
                    _jogging = null;
                    lease.Dispose();
                }
            }
        }
    }

    /// <summary>Why Go to is refused for <see cref="GoToXMm"/>, <see cref="GoToYMm"/>, in the job rules' words (as the command line's goto); null when it may go.</summary>
    public string? GoToProblem =>
        JobRules.Position(GoToXMm, _machine.Profile.X.TravelMm) is { } x ? $"go to X {N(GoToXMm)} mm: {x}"
        : JobRules.Position(GoToYMm, _machine.Profile.Y.TravelMm) is { } y ? $"go to Y {N(GoToYMm)} mm: {y}"
        : null;

    [RelayCommand(CanExecute = nameof(CanMove))]
    private Task GoToAsync() => GoToProblem is { } problem ? Refuse(problem) : Move("go to", string.Create(CultureInfo.InvariantCulture, $"Going to {GoToXMm:0.###}, {GoToYMm:0.###} mm, laser off…"), (moves, ct) => moves.GoToAsync(GoToXMm, GoToYMm, ct));

    /// <summary>Moves to the job's top-left corner (<see cref="EngraveJob.FrameBox"/>): an image's first pixel edge, a drawing's bounding box's corner.</summary>
    [RelayCommand(CanExecute = nameof(CanMoveToJob))]
    private Task GoToOriginAsync() => Move("go to the job's origin", "Going to the job's origin, laser off…", (moves, ct) =>
    {
        var (job, (left, top, _, _)) = RequireBox();
        return moves.GoToAsync(StageUnits.MicrostepsToMm(left, job.Spec.Profile.X.MicrostepUm), StageUnits.MicrostepsToMm(top, job.Spec.Profile.Y.MicrostepUm), ct);
    });

    /// <summary>
    /// Traces the job's outline with the laser off, so the user sees where it will land: an image's pixel grid, or the
    /// box around a drawing's planned paths (as <c>laserengrave frame</c> traces it).
    /// </summary>
    [RelayCommand(CanExecute = nameof(CanMoveToJob))]
    private Task FrameAsync() => Move("frame", "Tracing the job's frame, laser off…", (moves, ct) =>
    {
        var (_, (left, top, right, bottom)) = RequireBox();
        return moves.FrameAsync(left, top, right, bottom, visibleFrequencyHz: null, ct);
    });

    /// <summary>Fires a burst where the stage stands (the stage does not move), at the job's frequency.</summary>
    [RelayCommand(CanExecute = nameof(CanMove))]
    private Task TestFireAsync() => Run("test fire", $"Firing {TestFirePulses} pulses…", async (moves, ct) =>
    {
        if (TestFireProblem is { } problem)
        {
            throw new ArgumentException(problem);
        }

        var hz = _job.ToSettings().LaserFrequencyHz;
        var frequency = (int)Math.Round(hz, MidpointRounding.AwayFromZero);
        if (frequency < 1)
        {
            throw new ArgumentException($"laser frequency {N(hz)} Hz must be at least 1 Hz");
        }

        await moves.FirePulsesAsync(TestFirePulses, frequency, ct);
        await _machine.ReadLaserAsync(moves.Gate, ct);
    });

    /// <summary>Stops the test move, jog or homing under way (laser off); a run is stopped with its own Abort.</summary>
    [RelayCommand(CanExecute = nameof(CanStop))]
    private void Stop()
    {
        if (Activity.Current is { Kind: not MachineOperationKind.Run })
        {
            Activity.CancelCurrent();
        }
    }

    /// <summary>A machine, and nothing holding it (the interlock decides first).</summary>
    public bool CanMove => !Activity.IsBusy && _machine.IsConnected;

    /// <summary>As <see cref="CanMove"/>, with a planned image or drawing to go to or trace.</summary>
    public bool CanMoveToJob => CanMove && JobMoveUnavailableReason is null;

    /// <summary>Why Job origin and Frame have nothing to go to, one line for their tooltips; null when a job is planned.</summary>
    public string? JobMoveUnavailableReason => _job.Engraving is not null ? null
        : _job.ImageInfo is null && !_job.IsDrawing ? "open an image or drawing first"
        : "the job does not plan: see the fields marked in red";

    /// <summary>What the test move, jog, homing or connecting under way is doing, in words, for the run bar and this panel; null when none is.</summary>
    public string? MotionText => Activity.Current is { Kind: not MachineOperationKind.Run } op ? op.Doing : null;

    /// <summary>A test move, jog, homing or connect holds the machine and can be stopped (a run has its own Abort).</summary>
    public bool CanStop => Activity.Current is { Kind: not MachineOperationKind.Run };

    private void RefreshCommands()
    {
        JogCommand.NotifyCanExecuteChanged();
        GoToCommand.NotifyCanExecuteChanged();
        GoToOriginCommand.NotifyCanExecuteChanged();
        FrameCommand.NotifyCanExecuteChanged();
        TestFireCommand.NotifyCanExecuteChanged();
        StopCommand.NotifyCanExecuteChanged();
    }

    /// <summary>The planned job and the rectangle it burns in, microsteps, as the command line's frame takes it.</summary>
    private (EngraveJob Job, (long Left, long Top, long Right, long Bottom) Box) RequireBox()
    {
        var job = _job.Engraving ?? throw new ArgumentException("no job planned: open an image and give it a usable size first");
        return (job, job.FrameBox ?? throw new ArgumentException("the drawing has no path to frame"));
    }

    /// <summary>A move (the Devices test moves switch the laser off first); the positions are read afterwards.</summary>
    private Task Move(string what, string doing, Func<StageTestMoves, CancellationToken, Task<StagePosition>> move) => Run(what, doing, async (moves, ct) =>
    {
        try
        {
            await _machine.FollowAsync(move(moves, ct), ct);
        }
        finally
        {
            await _machine.ReadPositionsAsync(CancellationToken.None);
        }
    });

    private Task Refuse(string problem)
    {
        Error = problem;
        return Task.CompletedTask;
    }

    private async Task Run(string what, string doing, Func<StageTestMoves, CancellationToken, Task> action)
    {
        Error = null;
        var ran = await _machine.Guard(MachineOperation.TestMove(what, doing), async cancellationToken =>
        {
            var connection = _machine.RequireConnection();
            var moves = new StageTestMoves(connection.Stage, connection.Gate, connection.Profile, timeProvider: connection.TimeProvider);
            await action(moves, cancellationToken);
        });
        Error = ran ? _machine.Error : Activity.BusyMessage ?? _machine.Error;
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}
