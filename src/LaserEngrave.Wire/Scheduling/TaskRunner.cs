namespace LaserEngrave.Wire.Scheduling;

/// <summary>Finds the runner that goes with a clock: a clock that is also a runner (the simulation's) runs its own work.</summary>
public static class TaskRunner
{
    /// <summary>The thread pool, for real ports and the wall clock.</summary>
    public static ITaskRunner ThreadPool { get; } = new ThreadPoolRunner();

    /// <summary>The runner of <paramref name="time"/>: the simulation's loop for its virtual clock, else the thread pool.</summary>
    public static ITaskRunner For(TimeProvider time) => time as ITaskRunner ?? ThreadPool;

    /// <summary>Runs <paramref name="operation"/> on the runner of <paramref name="time"/>.</summary>
    public static Task Run(TimeProvider time, Func<Task> operation)
    {
        ArgumentNullException.ThrowIfNull(operation);
        return For(time).Run(async () =>
        {
            await operation();
            return true;
        });
    }

    private sealed class ThreadPoolRunner : ITaskRunner
    {
        public Task Start(Func<Task> loop) => Task.Run(loop);

        // Nothing to enter: the caller's own thread will do, and its awaits continue on the pool.
        public Task<T> Run<T>(Func<Task<T>> operation) => operation();
    }
}
