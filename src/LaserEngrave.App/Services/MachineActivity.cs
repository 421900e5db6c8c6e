using System.Diagnostics.CodeAnalysis;
using CommunityToolkit.Mvvm.ComponentModel;

namespace LaserEngrave.App.Services;

/// <summary>
/// What the machine is doing, in one place: a run, homing, a test move, connecting. While one operation holds the
/// machine every other machine command and every change to the job is refused with one line saying what is running.
/// </summary>
/// <remarks>The view-models observe <see cref="Current"/> to disable their commands; the API answers 409 with <see cref="BusyMessage"/>.</remarks>
public sealed partial class MachineActivity : ObservableObject
{
    private readonly Lock _lock = new();
    private Lease? _lease;
    private TaskCompletionSource _idle = NewIdle(completed: true);

    /// <summary>The operation holding the machine, or null when it is free.</summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(IsBusy), nameof(BusyMessage), nameof(JobLockMessage))]
    public partial MachineOperation? Current { get; private set; }

    public bool IsBusy => Current is not null;

    /// <summary>Why a machine command is refused now, one line; null when the machine is free.</summary>
    public string? BusyMessage => Current is { } op ? $"{op.Summary}: {op.Hint}" : null;

    /// <summary>Why the job cannot change now, one line; null when it can.</summary>
    public string? JobLockMessage => Current is { LocksJob: true } op ? $"{op.Summary}: the job cannot change until it ends" : null;

    /// <summary>Takes the machine for <paramref name="operation"/>; false (and the reason) when another operation holds it.</summary>
    public bool TryBegin(MachineOperation operation, [NotNullWhen(true)] out Lease? lease, [NotNullWhen(false)] out string? refusal)
    {
        ArgumentNullException.ThrowIfNull(operation);
        lock (_lock)
        {
            if (_lease is not null)
            {
                lease = null;
                refusal = $"{_lease.Operation.Summary}: {_lease.Operation.Hint}";
                return false;
            }

            lease = _lease = new Lease(this, operation);
            refusal = null;
            if (_idle.Task.IsCompleted)
            {
                _idle = NewIdle(completed: false);
            }
        }

        Current = operation;
        return true;
    }

    /// <summary>Takes the machine or throws <see cref="MachineBusyException"/> naming what holds it.</summary>
    public Lease Begin(MachineOperation operation) =>
        TryBegin(operation, out var lease, out var refusal) ? lease : throw new MachineBusyException(refusal);

    /// <summary>Throws <see cref="MachineBusyException"/> while an operation that fixes the job is under way.</summary>
    public void ThrowIfJobLocked()
    {
        if (JobLockMessage is { } message)
        {
            throw new MachineBusyException(message);
        }
    }

    /// <summary>Cancels the operation under way (a run is aborted through its own token, laser off first).</summary>
    public void CancelCurrent()
    {
        Lease? lease;
        lock (_lock)
        {
            lease = _lease;
        }

        lease?.Cancel();
    }

    /// <summary>Completes when no operation holds the machine.</summary>
    public Task WhenIdleAsync()
    {
        lock (_lock)
        {
            return _idle.Task;
        }
    }

    private void End(Lease lease)
    {
        TaskCompletionSource idle;
        lock (_lock)
        {
            if (!ReferenceEquals(_lease, lease))
            {
                return;
            }

            _lease = null;
            idle = _idle;
        }

        Current = null;
        idle.TrySetResult();
    }

    private static TaskCompletionSource NewIdle(bool completed)
    {
        var idle = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        if (completed)
        {
            idle.SetResult();
        }

        return idle;
    }

    /// <summary>The machine held by one operation until disposed; its token is cancelled by <see cref="CancelCurrent"/>.</summary>
    public sealed class Lease : IDisposable
    {
        private readonly MachineActivity _owner;
        private readonly CancellationTokenSource _cancel = new();

        internal Lease(MachineActivity owner, MachineOperation operation)
        {
            _owner = owner;
            Operation = operation;
        }

        public MachineOperation Operation { get; }

        public CancellationToken CancellationToken => _cancel.Token;

        internal void Cancel()
        {
            try
            {
                _cancel.Cancel();
            }
            catch (ObjectDisposedException)
            {
                // Ended meanwhile: nothing left to cancel.
            }
        }

        public void Dispose()
        {
            _owner.End(this);
            _cancel.Dispose();
        }
    }
}
