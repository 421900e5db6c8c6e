using System.ComponentModel;
using System.Reflection;
using System.Windows.Input;
using LaserEngrave.App.Services;
using Microsoft.AspNetCore.Components;

namespace LaserEngrave.App.Components;

/// <summary>
/// A view over view-models: it re-renders when one of them raises <see cref="INotifyPropertyChanged.PropertyChanged"/>
/// or one of their commands raises <see cref="ICommand.CanExecuteChanged"/>, from whatever thread, at most one render queued.
/// </summary>
/// <remarks>
/// A change the interlock refuses (<see cref="MachineBusyException"/>: the job is fixed while a run, homing or a test
/// move is under way) never ends the page's circuit: the views disable those inputs, and a change that races the lock is
/// shown as <see cref="Refusal"/> instead.
/// </remarks>
public abstract class BoundComponent : ComponentBase, IHandleEvent, IDisposable
{
    private readonly List<INotifyPropertyChanged> _models = [];
    private readonly List<ICommand> _commands = [];
    private int _pending;

    /// <summary>The interlock's last refusal of a change made in this view, one line; cleared by the next change that goes through.</summary>
    protected string? Refusal { get; private set; }

    async Task IHandleEvent.HandleEventAsync(EventCallbackWorkItem callback, object? arg)
    {
        try
        {
            var task = callback.InvokeAsync(arg);
            StateHasChanged();
            await task;
            Refusal = null;
        }
        catch (MachineBusyException ex)
        {
            Refusal = ex.Message;
        }

        StateHasChanged();
    }

    /// <summary>The view-models this view shows; subscribed when the component starts.</summary>
    protected abstract IEnumerable<INotifyPropertyChanged> ViewModels();

    protected override void OnInitialized()
    {
        foreach (var model in ViewModels())
        {
            model.PropertyChanged += OnChanged;
            _models.Add(model);
            foreach (var property in model.GetType().GetProperties(BindingFlags.Public | BindingFlags.Instance))
            {
                if (typeof(ICommand).IsAssignableFrom(property.PropertyType) && property.GetValue(model) is ICommand command)
                {
                    command.CanExecuteChanged += OnChanged;
                    _commands.Add(command);
                }
            }
        }
    }

    /// <summary>Whether a change of this property needs a render; all do unless a view says otherwise.</summary>
    protected virtual bool Renders(object? sender, string? propertyName) => true;

    private void OnChanged(object? sender, EventArgs e)
    {
        if (e is PropertyChangedEventArgs p && !Renders(sender, p.PropertyName))
        {
            return;
        }

        // Changes come from pool threads (a run reports every move); one render catches up with all of them.
        if (Interlocked.Exchange(ref _pending, 1) == 1)
        {
            return;
        }

        _ = InvokeAsync(() =>
        {
            Volatile.Write(ref _pending, 0);
            StateHasChanged();
        });
    }

    /// <summary>Starts a command and lets its end show through the view-model; the command reports its own failures.</summary>
    protected static void Launch(Func<Task> command) => _ = Task.Run(command).ContinueWith(t => _ = t.Exception, TaskScheduler.Default);

    public virtual void Dispose()
    {
        foreach (var model in _models)
        {
            model.PropertyChanged -= OnChanged;
        }

        foreach (var command in _commands)
        {
            command.CanExecuteChanged -= OnChanged;
        }

        GC.SuppressFinalize(this);
    }
}
