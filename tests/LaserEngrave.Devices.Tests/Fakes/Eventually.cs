namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>Real-time guards so that a broken test fails instead of hanging.</summary>
public static class Eventually
{
    /// <summary>Generous wall-clock bound for things that happen at once in virtual time.</summary>
    public static readonly TimeSpan Limit = TimeSpan.FromSeconds(10);

    public static async Task TrueAsync(Func<bool> condition, string what)
    {
        var deadline = DateTime.UtcNow + Limit;
        while (!condition())
        {
            if (DateTime.UtcNow > deadline)
            {
                throw new TimeoutException($"never happened: {what}");
            }

            await Task.Delay(1);
        }
    }

    public static Task<T> Within<T>(this Task<T> task) => task.WaitAsync(Limit);

    public static Task Within(this Task task) => task.WaitAsync(Limit);

    /// <summary>Asserts the task has not completed after giving the system a real moment to complete it wrongly.</summary>
    public static async Task AssertStillPendingAsync(Task task)
    {
        await Task.Delay(50);
        Assert.False(task.IsCompleted, $"expected the task to be still waiting, but it is {task.Status}: {task.Exception?.InnerException?.Message}");
    }
}
