using System.Diagnostics;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>Helpers for tests that run the code under test and its fake devices on the simulation's loop (docs/simulator.md).</summary>
public static class VirtualTime
{
    /// <summary>Runs <paramref name="body"/> as one operation on the loop of <paramref name="time"/>, or directly on any other clock.</summary>
    /// <remarks>On the loop, a body that waits for something nobody will do fails with a <see cref="SimulationDeadlockException"/>;
    /// <see cref="Eventually.Within(Task)"/> only bounds a test that is broken in some other way. Work that reached the loop
    /// from another thread during the body (something that left the loop) fails the test: the result could depend on timing.</remarks>
    public static async Task RunTestAsync(this TimeProvider time, Func<Task> body)
    {
        if (time is not VirtualTimeProvider loop)
        {
            await body().Within();
            return;
        }

        var foreign = loop.Loop.ForeignPosts;
        await loop.Run(async () =>
        {
            await body();
            return true;
        }).Within();
        Assert.True(loop.Loop.ForeignPosts == foreign, $"{loop.Loop.ForeignPosts - foreign} work item(s) reached the loop from another thread");
    }

    /// <summary>Waits until nothing is left to do at this virtual instant (every reply read, every event raised) without moving the clock.</summary>
    /// <remarks>A timer due now fires only once the loop has no ready work left, after timers already due now.</remarks>
    public static async Task SettleAsync(this VirtualTimeProvider time)
    {
        var quiet = new TaskCompletionSource();
        using var timer = time.CreateTimer(static s => ((TaskCompletionSource)s!).TrySetResult(), quiet, TimeSpan.Zero, Timeout.InfiniteTimeSpan);
        await quiet.Task;
    }

    /// <summary>Asserts <paramref name="task"/> is still waiting once everything that could complete it at this instant has run.</summary>
    public static async Task AssertStillPendingAsync(this VirtualTimeProvider time, Task task)
    {
        await time.SettleAsync();
        Assert.False(task.IsCompleted, $"expected the task to be still waiting, but it is {task.Status}: {task.Exception?.InnerException?.Message}");
    }

    /// <summary>Like <c>Assert.ThrowsAsync</c> (the exact type), awaited on the caller's loop.</summary>
    public static async Task<T> ThrowsAsync<T>(Task task)
        where T : Exception
    {
        try
        {
            await task;
        }
        catch (Exception ex)
        {
            return Assert.IsType<T>(ex);
        }

        Assert.Fail($"expected {typeof(T).Name}, but the task completed");
        throw new UnreachableException();
    }
}
