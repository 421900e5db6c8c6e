namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>Wall-clock guards so that a broken test fails instead of hanging.</summary>
/// <remarks>
/// Tests on a virtual clock need none of these to be correct: on <see cref="VirtualTime"/>'s loop nothing happens
/// between steps, and on a <c>FakeTimeProvider</c> time stands still. <see cref="Within(Task)"/> only bounds how long
/// a broken test can hang; <see cref="AssertStillPendingAsync"/> is for real ports (ptys), where only the wall clock can tell.
/// </remarks>
public static class Eventually
{
    /// <summary>Generous wall-clock bound for things that happen at once in virtual time.</summary>
    public static readonly TimeSpan Limit = TimeSpan.FromSeconds(10);

    public static Task<T> Within<T>(this Task<T> task) => task.WaitAsync(Limit);

    public static Task Within(this Task task) => task.WaitAsync(Limit);

    /// <summary>Asserts a read on a real port has not completed after giving the OS a real moment to complete it wrongly.</summary>
    public static async Task AssertStillPendingAsync(Task task)
    {
        await Task.Delay(50);
        Assert.False(task.IsCompleted, $"expected the task to be still waiting, but it is {task.Status}: {task.Exception?.InnerException?.Message}");
    }
}
